# 32-bit ARM Linux (ARMv7-A, hard-float ABI: Debian's armhf) with arm-linux-gnueabihf-g++, for
# running the host tests on a 32-bit ARM target under qemu-arm: the same test binaries as on
# x86-64 must pass there, and the frame-hash test proves the frames bit-identical.
#
#   bash scripts/ci_armhf.sh       (sysroot + configure + build + ctest: what CI runs)
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

set(CMAKE_SYSTEM_NAME Linux)
set(CMAKE_SYSTEM_PROCESSOR arm)
set(CMAKE_LIBRARY_ARCHITECTURE arm-linux-gnueabihf)

set(CMAKE_C_COMPILER arm-linux-gnueabihf-gcc)
set(CMAKE_CXX_COMPILER arm-linux-gnueabihf-g++)

# The private sysroot of armhf packages.
if(NOT LR_ARMHF_SYSROOT)
  if(DEFINED ENV{LR_ARMHF_SYSROOT})
    set(LR_ARMHF_SYSROOT "$ENV{LR_ARMHF_SYSROOT}")
  else()
    get_filename_component(LR_ARMHF_SYSROOT "${CMAKE_CURRENT_LIST_DIR}/../build/armhf-sysroot"
                           ABSOLUTE)
  endif()
endif()
# try_compile() projects re-read this file in a fresh scope: pass the root on to them.
list(APPEND CMAKE_TRY_COMPILE_PLATFORM_VARIABLES LR_ARMHF_SYSROOT)

# The cross toolchain's own C library (the compiler already links against it; listed so that
# find_*() may see it too).
set(LR_ARMHF_TOOLCHAIN_ROOT /usr/arm-linux-gnueabihf)

# find_*(): programs come from the host; libraries, headers and packages only from the sysroot
# and the toolchain's root, never from the host's /usr.
set(CMAKE_FIND_ROOT_PATH "${LR_ARMHF_SYSROOT}" "${LR_ARMHF_TOOLCHAIN_ROOT}")
set(CMAKE_FIND_ROOT_PATH_MODE_PROGRAM NEVER)
set(CMAKE_FIND_ROOT_PATH_MODE_LIBRARY ONLY)
set(CMAKE_FIND_ROOT_PATH_MODE_INCLUDE ONLY)
set(CMAKE_FIND_ROOT_PATH_MODE_PACKAGE ONLY)

# libpng and zlib linked statically (see above). Cache entries, so FindPNG/FindZLIB take them as
# found; a wrong or missing sysroot fails at link time with these paths in the message.
set(_lr_armhf_libdir "${LR_ARMHF_SYSROOT}/usr/lib/arm-linux-gnueabihf")
set(PNG_LIBRARY "${_lr_armhf_libdir}/libpng16.a" CACHE FILEPATH "libpng (armhf, static)")
set(ZLIB_LIBRARY "${_lr_armhf_libdir}/libz.a" CACHE FILEPATH "zlib (armhf, static)")

# Running target programs on the build machine.
find_program(LR_QEMU_ARM qemu-arm)
if(NOT LR_QEMU_ARM)
  message(FATAL_ERROR "qemu-arm not found: install qemu-user (scripts/setup.sh test does)")
endif()
set(CMAKE_CROSSCOMPILING_EMULATOR "${LR_QEMU_ARM};-L;${LR_ARMHF_TOOLCHAIN_ROOT}")
