# The GNU Arm Embedded toolchain (arm-none-eabi-gcc/g++), bare metal: the part every Arm
# Cortex-M toolchain file shares. Do not use this file directly: include it from a CPU file
# (cortex-m0plus.cmake, cortex-m4f.cmake, cortex-m7.cmake, cortex-m33.cmake), which sets first
#   LR_CPU_FLAGS  the compiler's CPU and ABI flags (they also select the multilib of libgcc)
#   LR_FW_CPU     the CPU's name, which firmware/boards.cmake checks a board against
#   LR_FW_BOARD   (a cache entry) the board images are linked for unless they name another
#
# The compilers are looked up on PATH. To use another installation, put its bin/ first on PATH
# or set ARM_NONE_EABI_ROOT (environment or -D) to the directory that holds bin/.
#
# How the flags reach the compiler, and why they must not be given with -DCMAKE_CXX_FLAGS:
# see toolchain/cortex-m4f.cmake.

if(NOT LR_CPU_FLAGS OR NOT LR_FW_CPU)
  message(FATAL_ERROR "arm-none-eabi.cmake: include it from a CPU file that sets LR_CPU_FLAGS "
                      "and LR_FW_CPU (e.g. toolchain/cortex-m4f.cmake)")
endif()

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

# Every function and object in its own section, so that --gc-sections drops what is unused.
set(CMAKE_C_FLAGS_INIT "${LR_CPU_FLAGS} -ffunction-sections -fdata-sections")
set(CMAKE_CXX_FLAGS_INIT
    "${LR_CPU_FLAGS} -fno-exceptions -fno-rtti -ffunction-sections -fdata-sections")
set(CMAKE_ASM_FLAGS_INIT "${LR_CPU_FLAGS}")

# CMake passes CMAKE_<LANG>_FLAGS to the link step too, so the CPU flags select the multilib
# (libgcc's directory, e.g. thumb/v6-m/nofp or thumb/v7e-m+fp/hard: `arm-none-eabi-gcc
# ${LR_CPU_FLAGS} -print-multi-directory`); the linker flags only add section garbage
# collection.
set(CMAKE_EXE_LINKER_FLAGS_INIT "-Wl,--gc-sections")
