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

set(LR_CROSS_TRIPLE aarch64-linux-gnu)
set(LR_CROSS_PROCESSOR aarch64)
set(LR_CROSS_SYSROOT_VAR LR_ARM64_SYSROOT)
set(LR_CROSS_SYSROOT_DIR arm64-sysroot)
set(LR_CROSS_QEMU qemu-aarch64)
include(${CMAKE_CURRENT_LIST_DIR}/linux-cross.cmake)
