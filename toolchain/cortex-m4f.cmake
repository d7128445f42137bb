# Cortex-M4F (ARMv7E-M with the single-precision FPU, hard-float ABI) with arm-none-eabi-gcc.
# Images run on QEMU's mps2-an386 (Cortex-M4 with FPU) by default: LR_FW_BOARD below.
#
#   cmake --preset cortex-m4f && cmake --build --preset cortex-m4f
#   (or: cmake -S . -B build/m4f -DCMAKE_TOOLCHAIN_FILE=toolchain/cortex-m4f.cmake: host tools
#   are off when cross-compiling)
#
# The other Cortex-M files (cortex-m0plus.cmake, cortex-m7.cmake, cortex-m33.cmake) work the same
# way; what follows about flags holds for all of them.
#
# Adding compiler flags
# ---------------------
# The CPU flags below (LR_CPU_FLAGS) go into CMAKE_<LANG>_FLAGS_INIT (arm-none-eabi.cmake sets
# it). CMake builds the cache variable CMAKE_<LANG>_FLAGS from them ONLY when that variable is
# not in the cache yet, as
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

# -mfpu=fpv4-sp-d16: the M4's FPU, FPv4 single precision only, S0-S31 (the "d16" of the name:
# they overlay 16 double registers, which hold no double arithmetic here). Multilib
# thumb/v7e-m+fp/hard.
set(LR_CPU_FLAGS "-mcpu=cortex-m4 -mthumb -mfpu=fpv4-sp-d16 -mfloat-abi=hard")
set(LR_FW_CPU cortex-m4f)
set(LR_FW_BOARD mps2-an386 CACHE STRING "Board (firmware/boards.cmake) firmware images are linked for")

# Compilers, CMAKE_<LANG>_FLAGS_INIT from LR_CPU_FLAGS, link flags.
include(${CMAKE_CURRENT_LIST_DIR}/arm-none-eabi.cmake)
