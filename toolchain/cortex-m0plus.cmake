# Cortex-M0+ (ARMv6-M: Thumb-1 plus a few 32-bit instructions, no divide, no FPU; soft-float
# ABI) with arm-none-eabi-gcc. Multilib thumb/v6-m/nofp.
#
#   cmake --preset cortex-m0plus && cmake --build --preset cortex-m0plus
#
# Board: QEMU's microbit (nRF51, a Cortex-M0: the same ARMv6-M instruction set) by default, with
# 16 KB of RAM. Images that need more RAM link for mps2-an385 (lr_firmware_app(... BOARD
# mps2-an385), or -DLR_FW_BOARD=mps2-an385 at the first configure): a Cortex-M3 that runs the
# ARMv6-M code unchanged (firmware/boards.cmake says why that is faithful).
#
# Flags: add them through CFLAGS/CXXFLAGS at the first configure or in this file, never with
# -DCMAKE_CXX_FLAGS, which replaces the CPU flags below (see toolchain/cortex-m4f.cmake).

# -mfloat-abi=soft is the default for this CPU; spelled out so the ABI is explicit.
set(LR_CPU_FLAGS "-mcpu=cortex-m0plus -mthumb -mfloat-abi=soft")
set(LR_FW_CPU cortex-m0plus)
set(LR_FW_BOARD microbit CACHE STRING "Board (firmware/boards.cmake) firmware images are linked for")

include(${CMAKE_CURRENT_LIST_DIR}/arm-none-eabi.cmake)
