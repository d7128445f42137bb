# Cortex-M4F (ARMv7E-M with the single-precision FPU, hard-float ABI) with arm-none-eabi-gcc.
#
#   cmake --preset cortex-m4f && cmake --build --preset cortex-m4f
#   (or: cmake -S . -B build/m4f -DCMAKE_TOOLCHAIN_FILE=toolchain/cortex-m4f.cmake -DLR_HOST=OFF)
#
# Adding compiler flags
# ---------------------
# The CPU flags below go into CMAKE_<LANG>_FLAGS_INIT. CMake builds the cache variable
# CMAKE_<LANG>_FLAGS from them ONLY when that variable is not in the cache yet, as
#   CMAKE_CXX_FLAGS = "$ENV{CXXFLAGS} ${CMAKE_CXX_FLAGS_INIT}"     (C: CFLAGS, links: LDFLAGS)
# so there are two ways to add flags to a cross build:
#   1. the environment, at the first configure of a build tree (or with `cmake --fresh`):
#        CXXFLAGS="-g3 -DLR_SOMETHING" cmake --preset cortex-m4f
#   2. editing this file (for flags every Cortex-M4F build needs), then reconfiguring fresh.
# Do NOT pass -DCMAKE_CXX_FLAGS=... (or -DCMAKE_C_FLAGS, or the preset's cacheVariables) to a
# cross build: a value given on the command line puts CMAKE_CXX_FLAGS into the cache before
# CMake looks at *_FLAGS_INIT, so the init value is never used and the CPU flags silently
# disappear. The compiler then falls back to its default (-marm, ARMv4T, soft float) and the
# objects either fail to link against the hard-float multilib or run the wrong instructions.
# Per-target additions belong in CMakeLists.txt (target_compile_options), per-configuration
# ones in CMAKE_CXX_FLAGS_<CONFIG> (e.g. -DCMAKE_CXX_FLAGS_RELEASE="-Os -DNDEBUG"), which does
# not touch the CPU flags.

include(${CMAKE_CURRENT_LIST_DIR}/arm-none-eabi.cmake)

set(LR_CPU_FLAGS "-mcpu=cortex-m4 -mthumb -mfpu=fpv4-sp-d16 -mfloat-abi=hard")

# Every function and object in its own section, so that --gc-sections drops what is unused.
set(CMAKE_C_FLAGS_INIT "${LR_CPU_FLAGS} -ffunction-sections -fdata-sections")
set(CMAKE_CXX_FLAGS_INIT "${LR_CPU_FLAGS} -fno-exceptions -fno-rtti -ffunction-sections -fdata-sections")
set(CMAKE_ASM_FLAGS_INIT "${LR_CPU_FLAGS}")

# CMake passes CMAKE_<LANG>_FLAGS to the link step too (the CPU flags select the multilib:
# thumb/v7e-m+fp/hard); the linker flags only add section garbage collection.
set(CMAKE_EXE_LINKER_FLAGS_INIT "-Wl,--gc-sections")
