# Cortex-M7 (ARMv7E-M with the double-precision FPv5 FPU, hard-float ABI) with arm-none-eabi-gcc.
# Multilib thumb/v7e-m+dp/hard.
#
#   cmake --preset cortex-m7 && cmake --build --preset cortex-m7
#
# Board: QEMU's mps2-an500 (Cortex-M7 with FPU) by default. QEMU models neither the M7's caches
# nor its TCMs: timings under QEMU say nothing about the M7's dual-issue pipeline.
#
# Flags: add them through CFLAGS/CXXFLAGS at the first configure or in this file, never with
# -DCMAKE_CXX_FLAGS, which replaces the CPU flags below (see toolchain/cortex-m4f.cmake).

# -mfpu=fpv5-d16: FPv5 with double precision and D0-D15 (the M7's full FPU option; parts with the
# single-precision option need fpv5-sp-d16 and multilib thumb/v7e-m+fp/hard instead).
set(LR_CPU_FLAGS "-mcpu=cortex-m7 -mthumb -mfpu=fpv5-d16 -mfloat-abi=hard")
set(LR_FW_CPU cortex-m7)
set(LR_FW_BOARD mps2-an500 CACHE STRING "Board (firmware/boards.cmake) firmware images are linked for")

include(${CMAKE_CURRENT_LIST_DIR}/arm-none-eabi.cmake)
