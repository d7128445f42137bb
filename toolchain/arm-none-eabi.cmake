# The GNU Arm Embedded toolchain (arm-none-eabi-gcc/g++), bare metal: the part every Arm
# Cortex-M toolchain file shares. Do not use this file directly: include it from a CPU file
# (cortex-m4f.cmake, ...) that sets the CPU flags.
#
# The compilers are looked up on PATH. To use another installation, put its bin/ first on PATH
# or set ARM_NONE_EABI_ROOT (environment or -D) to the directory that holds bin/.

set(CMAKE_SYSTEM_NAME Generic)
set(CMAKE_SYSTEM_PROCESSOR arm)

if(NOT ARM_NONE_EABI_ROOT AND DEFINED ENV{ARM_NONE_EABI_ROOT})
  set(ARM_NONE_EABI_ROOT "$ENV{ARM_NONE_EABI_ROOT}")
endif()
if(ARM_NONE_EABI_ROOT)
  set(_lr_arm_prefix "${ARM_NONE_EABI_ROOT}/bin/arm-none-eabi-")
else()
  set(_lr_arm_prefix "arm-none-eabi-")
endif()
# try_compile() projects re-read this file in a fresh scope: pass the root on to them.
list(APPEND CMAKE_TRY_COMPILE_PLATFORM_VARIABLES ARM_NONE_EABI_ROOT)

set(CMAKE_C_COMPILER "${_lr_arm_prefix}gcc")
set(CMAKE_CXX_COMPILER "${_lr_arm_prefix}g++")
set(CMAKE_ASM_COMPILER "${_lr_arm_prefix}gcc")
# objcopy, objdump, size, nm: CMake finds them next to the compiler (same prefix).

# There is no OS to run a test executable on, and linking one would need a linker script and
# startup code: compiler checks build a static library instead.
set(CMAKE_TRY_COMPILE_TARGET_TYPE STATIC_LIBRARY)

# find_*(): programs (tools that run on the build machine) come from the host; libraries,
# headers and packages only from the target's root (CMAKE_FIND_ROOT_PATH / CMAKE_SYSROOT), never
# from the host's /usr.
set(CMAKE_FIND_ROOT_PATH_MODE_PROGRAM NEVER)
set(CMAKE_FIND_ROOT_PATH_MODE_LIBRARY ONLY)
set(CMAKE_FIND_ROOT_PATH_MODE_INCLUDE ONLY)
set(CMAKE_FIND_ROOT_PATH_MODE_PACKAGE ONLY)
