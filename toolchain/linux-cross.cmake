# The part toolchain/arm-linux-gnueabihf.cmake and toolchain/aarch64-linux-gnu.cmake share: a
# Debian cross compiler, a private sysroot of Debian packages, and qemu-user to run the
# target's programs. Not for direct use: the including file sets
#   LR_CROSS_TRIPLE       the GNU triple (compiler prefix, library architecture, /usr/<triple>)
#   LR_CROSS_PROCESSOR    CMAKE_SYSTEM_PROCESSOR
#   LR_CROSS_SYSROOT_VAR  the name of the sysroot variable (-D or environment), e.g. LR_ARMHF_SYSROOT
#   LR_CROSS_SYSROOT_DIR  its default folder under build/
#   LR_CROSS_QEMU         the qemu-user program (qemu-arm, qemu-aarch64)

set(CMAKE_SYSTEM_NAME Linux)
set(CMAKE_SYSTEM_PROCESSOR ${LR_CROSS_PROCESSOR})
set(CMAKE_LIBRARY_ARCHITECTURE ${LR_CROSS_TRIPLE})

set(CMAKE_C_COMPILER ${LR_CROSS_TRIPLE}-gcc)
set(CMAKE_CXX_COMPILER ${LR_CROSS_TRIPLE}-g++)

# The private sysroot: -D<var>, else the environment variable of that name, else build/<dir>.
if(NOT ${LR_CROSS_SYSROOT_VAR})
  if(DEFINED ENV{${LR_CROSS_SYSROOT_VAR}})
    set(${LR_CROSS_SYSROOT_VAR} "$ENV{${LR_CROSS_SYSROOT_VAR}}")
  else()
    get_filename_component(${LR_CROSS_SYSROOT_VAR}
                           "${CMAKE_CURRENT_LIST_DIR}/../build/${LR_CROSS_SYSROOT_DIR}" ABSOLUTE)
  endif()
endif()
set(_lr_cross_sysroot "${${LR_CROSS_SYSROOT_VAR}}")
# try_compile() projects re-read the toolchain file in a fresh scope: pass the root on to them.
list(APPEND CMAKE_TRY_COMPILE_PLATFORM_VARIABLES ${LR_CROSS_SYSROOT_VAR})

# The cross toolchain's own C library (the compiler already links against it; listed so that
# find_*() may see it too).
set(_lr_cross_toolchain_root /usr/${LR_CROSS_TRIPLE})

# find_*(): programs come from the host; libraries, headers and packages only from the sysroot
# and the toolchain's root, never from the host's /usr.
set(CMAKE_FIND_ROOT_PATH "${_lr_cross_sysroot}" "${_lr_cross_toolchain_root}")
set(CMAKE_FIND_ROOT_PATH_MODE_PROGRAM NEVER)
set(CMAKE_FIND_ROOT_PATH_MODE_LIBRARY ONLY)
set(CMAKE_FIND_ROOT_PATH_MODE_INCLUDE ONLY)
set(CMAKE_FIND_ROOT_PATH_MODE_PACKAGE ONLY)

# libpng and zlib linked statically. Cache entries, so FindPNG/FindZLIB take them as found; a
# wrong or missing sysroot fails at link time with these paths in the message.
set(_lr_cross_libdir "${_lr_cross_sysroot}/usr/lib/${LR_CROSS_TRIPLE}")
set(PNG_LIBRARY "${_lr_cross_libdir}/libpng16.a" CACHE FILEPATH "libpng (${LR_CROSS_TRIPLE}, static)")
set(ZLIB_LIBRARY "${_lr_cross_libdir}/libz.a" CACHE FILEPATH "zlib (${LR_CROSS_TRIPLE}, static)")

# Running target programs on the build machine.
find_program(LR_QEMU_USER ${LR_CROSS_QEMU})
if(NOT LR_QEMU_USER)
  message(FATAL_ERROR "${LR_CROSS_QEMU} not found: install qemu-user (scripts/setup.sh test does)")
endif()
set(CMAKE_CROSSCOMPILING_EMULATOR "${LR_QEMU_USER};-L;${_lr_cross_toolchain_root}")
