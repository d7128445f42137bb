# 64-bit ARM Linux (AArch64, Debian's arm64) with aarch64-linux-gnu-g++, for running the core's
# tests on a 64-bit ARM target under qemu-aarch64: the frame-hash test must pass there as on
# x86-64 and 32-bit ARM, proving the frames bit-identical. The 64-bit sibling of
# toolchain/arm-linux-gnueabihf.cmake, built the same way.
#
#   bash scripts/ci_aarch64.sh     (sysroot + configure + build + the core tests: what CI runs)
#   or: bash scripts/armhf_sysroot.sh --arch arm64 && cmake --preset aarch64 \
#       && cmake --build --preset aarch64
#
# Needs (Debian 12): g++-aarch64-linux-gnu (compiler, glibc and libstdc++ for arm64 under
# /usr/aarch64-linux-gnu) and qemu-user (qemu-aarch64); scripts/setup.sh test installs both.
#
# Libraries: GoogleTest, libpng and zlib for arm64 come from Debian's arm64 packages unpacked by
# `scripts/armhf_sysroot.sh --arch arm64` into a private sysroot, build/arm64-sysroot by default
# (another folder: -DLR_ARM64_SYSROOT=/path or the environment variable of the same name at the
# first configure). The host's dpkg never learns about arm64.
#   - find_package(GTest) finds the sysroot's usr/lib/aarch64-linux-gnu/cmake/GTest config
#     (CMAKE_FIND_ROOT_PATH + CMAKE_LIBRARY_ARCHITECTURE below);
#   - find_package(PNG) / ZLIB are pointed at the static archives (libpng16.a, libz.a), so test
#     executables need no library from the sysroot at run time: only glibc and libstdc++, which
#     qemu-aarch64 finds under its -L prefix (/usr/aarch64-linux-gnu).
#
# Running: CMAKE_CROSSCOMPILING_EMULATOR makes CTest and add_custom_command (lineraster-asset at
# build time) run the AArch64 executables through `qemu-aarch64 -L /usr/aarch64-linux-gnu`;
# tests that start another of the project's programs through a shell put the same prefix in
# front of it (LR_RUN_PREFIX in tests/CMakeLists.txt). No binfmt_misc registration is needed.
#
# Compiler flags: the compiler's Debian defaults (-march=armv8-a), the ABI the arm64 packages
# were built for; nothing is added here. Extra flags go through CXXFLAGS at the first configure.
# Unlike x86-64 (no -mfma) and armhf, GCC fuses a * b + c into FMA instructions here (its default
# -ffp-contract=fast, also with -std=c++20): the host code's double arithmetic (mesh fitting, the
# conversions to fixed point in host_sim) may round differently from x86-64's. The core has no
# floating point in its render path, and the frame-hash test passes with the fused host code as
# it is, so -ffp-contract=off is not added; should a hash ever differ, look there first.

set(CMAKE_SYSTEM_NAME Linux)
set(CMAKE_SYSTEM_PROCESSOR aarch64)
set(CMAKE_LIBRARY_ARCHITECTURE aarch64-linux-gnu)

set(CMAKE_C_COMPILER aarch64-linux-gnu-gcc)
set(CMAKE_CXX_COMPILER aarch64-linux-gnu-g++)

# The private sysroot of arm64 packages.
if(NOT LR_ARM64_SYSROOT)
  if(DEFINED ENV{LR_ARM64_SYSROOT})
    set(LR_ARM64_SYSROOT "$ENV{LR_ARM64_SYSROOT}")
  else()
    get_filename_component(LR_ARM64_SYSROOT "${CMAKE_CURRENT_LIST_DIR}/../build/arm64-sysroot"
                           ABSOLUTE)
  endif()
endif()
# try_compile() projects re-read this file in a fresh scope: pass the root on to them.
list(APPEND CMAKE_TRY_COMPILE_PLATFORM_VARIABLES LR_ARM64_SYSROOT)

# The cross toolchain's own C library (the compiler already links against it; listed so that
# find_*() may see it too).
set(LR_ARM64_TOOLCHAIN_ROOT /usr/aarch64-linux-gnu)

# find_*(): programs come from the host; libraries, headers and packages only from the sysroot
# and the toolchain's root, never from the host's /usr.
set(CMAKE_FIND_ROOT_PATH "${LR_ARM64_SYSROOT}" "${LR_ARM64_TOOLCHAIN_ROOT}")
set(CMAKE_FIND_ROOT_PATH_MODE_PROGRAM NEVER)
set(CMAKE_FIND_ROOT_PATH_MODE_LIBRARY ONLY)
set(CMAKE_FIND_ROOT_PATH_MODE_INCLUDE ONLY)
set(CMAKE_FIND_ROOT_PATH_MODE_PACKAGE ONLY)

# libpng and zlib linked statically (see above). Cache entries, so FindPNG/FindZLIB take them as
# found; a wrong or missing sysroot fails at link time with these paths in the message.
set(_lr_arm64_libdir "${LR_ARM64_SYSROOT}/usr/lib/aarch64-linux-gnu")
set(PNG_LIBRARY "${_lr_arm64_libdir}/libpng16.a" CACHE FILEPATH "libpng (arm64, static)")
set(ZLIB_LIBRARY "${_lr_arm64_libdir}/libz.a" CACHE FILEPATH "zlib (arm64, static)")

# Running target programs on the build machine.
find_program(LR_QEMU_AARCH64 qemu-aarch64)
if(NOT LR_QEMU_AARCH64)
  message(FATAL_ERROR "qemu-aarch64 not found: install qemu-user (scripts/setup.sh test does)")
endif()
set(CMAKE_CROSSCOMPILING_EMULATOR "${LR_QEMU_AARCH64};-L;${LR_ARM64_TOOLCHAIN_ROOT}")
