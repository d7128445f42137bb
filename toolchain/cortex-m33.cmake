# Cortex-M33 (ARMv8-M Mainline with the single-precision FPv5 FPU, hard-float ABI) with
# arm-none-eabi-gcc. Multilib thumb/v8-m.main+fp/hard.
#
#   cmake --preset cortex-m33 && cmake --build --preset cortex-m33
#
# Board: QEMU's mps2-an505 (the Arm IoT Kit: Cortex-M33 with TrustZone and FPU) by default. The
# image runs in Secure state, where the core leaves reset; no Non-secure image, no -mcmse
# (firmware/common/mps2_an505.ld).
#
# Flags: add them through CFLAGS/CXXFLAGS at the first configure or in this file, never with
# -DCMAKE_CXX_FLAGS, which replaces the CPU flags below (see toolchain/cortex-m4f.cmake).

set(LR_CPU_FLAGS "-mcpu=cortex-m33 -mthumb -mfpu=fpv5-sp-d16 -mfloat-abi=hard")
set(LR_FW_CPU cortex-m33)
set(LR_FW_BOARD mps2-an505 CACHE STRING "Board (firmware/boards.cmake) firmware images are linked for")

include(${CMAKE_CURRENT_LIST_DIR}/arm-none-eabi.cmake)
