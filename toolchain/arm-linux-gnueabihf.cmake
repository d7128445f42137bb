# 32-bit ARM Linux (ARMv7-A, hard-float ABI: Debian's armhf) with arm-linux-gnueabihf-g++, for
# running the host tests on a 32-bit ARM target under qemu-arm: the same test binaries as on
# x86-64 must pass there, and the frame-hash test proves the frames bit-identical.
#
#   bash scripts/ci_armhf.sh       (sysroot + configure + the core, hal and host tests: what CI runs)
#   or: bash scripts/armhf_sysroot.sh && cmake --preset armhf && cmake --build --preset armhf \
#       && ctest --preset armhf
#
# Needs (Debian 12): g++-arm-linux-gnueabihf (compiler, glibc and libstdc++ for armhf under
# /usr/arm-linux-gnueabihf) and qemu-user (qemu-arm); scripts/setup.sh test installs both.
#
# Libraries: GoogleTest, libpng and zlib for armhf come from Debian's armhf packages unpacked by
# scripts/armhf_sysroot.sh into a private sysroot, build/armhf-sysroot by default (another
# folder: -DLR_ARMHF_SYSROOT=/path or the environment variable of the same name at the first
# configure). The host's dpkg never learns about armhf.
#   - find_package(GTest) finds the sysroot's usr/lib/arm-linux-gnueabihf/cmake/GTest config
#     (CMAKE_FIND_ROOT_PATH + CMAKE_LIBRARY_ARCHITECTURE below);
#   - find_package(PNG) / ZLIB are pointed at the static archives (libpng16.a, libz.a), so test
#     executables need no library from the sysroot at run time: only glibc and libstdc++, which
#     qemu-arm finds under its -L prefix (/usr/arm-linux-gnueabihf).
#
# Running: CMAKE_CROSSCOMPILING_EMULATOR makes CTest (add_test with a target, gtest discovery)
# and add_custom_command (lineraster-asset at build time) run the ARM executables through
# `qemu-arm -L /usr/arm-linux-gnueabihf`. Tests that start another ARM program through a shell
# (cli_test, asset_round_trip_test) put the same prefix in front of it (LR_RUN_PREFIX in
# tests/CMakeLists.txt), so no binfmt_misc registration is needed.
#
# Compiler flags: the compiler's Debian defaults (-march=armv7-a+fp -mfpu=vfpv3-d16 -mthumb
# -mfloat-abi=hard), the ABI the armhf packages were built for; nothing is added here. Extra flags
# go through CXXFLAGS at the first configure, as for toolchain/cortex-m4f.cmake.

set(LR_CROSS_TRIPLE arm-linux-gnueabihf)
set(LR_CROSS_PROCESSOR arm)
set(LR_CROSS_SYSROOT_VAR LR_ARMHF_SYSROOT)
set(LR_CROSS_SYSROOT_DIR armhf-sysroot)
set(LR_CROSS_QEMU qemu-arm)
include(${CMAKE_CURRENT_LIST_DIR}/linux-cross.cmake)
