# The boards firmware images are linked for, each a QEMU 7.2 machine. The memory maps, with their
# sources in QEMU, are in the header of each linker script (common/*.ld); the sections all boards
# share are in common/cortex_m_sections.ld.
#
#   board        QEMU machine  core (QEMU)  FLASH (code)           RAM (data, bss, stack)   cores built for it
#   microbit     microbit      Cortex-M0    256 KB at 0x00000000    16 KB at 0x20000000      cortex-m0plus
#   mps2-an385   mps2-an385    Cortex-M3    4 MB at 0x00000000      4 MB at 0x20000000       cortex-m0plus
#   mps2-an386   mps2-an386    Cortex-M4F   4 MB at 0x00000000      4 MB at 0x20000000       cortex-m4f
#   mps2-an500   mps2-an500    Cortex-M7    4 MB at 0x00000000      4 MB at 0x20000000       cortex-m7, cortex-m4f
#   mps2-an505   mps2-an505    Cortex-M33   4 MB at 0x10000000 (S)  4 MB at 0x38000000 (S)   cortex-m33
#
# Cortex-M0+ images on the M0 and the M3: QEMU has no Cortex-M0+ machine. The micro:bit's M0 is
# ARMv6-M like the M0+, and executes the same instructions with the same results. mps2-an385 runs
# the M0+ images that need more than 16 KB of RAM: ARMv6-M is a subset of ARMv7-M (every ARMv6-M
# encoding exists in ARMv7-M with the same meaning), so the M3 executes exactly the instruction
# stream the M0+ would, and an instruction count under QEMU (which counts instructions, not
# cycles) is that of the M0+ image. What differs is only what the code does not rely on: cycle
# timings, and unaligned word/halfword accesses, which ARMv6-M always traps and ARMv7-M allows
# by default. startup.cpp sets CCR.UNALIGN_TRP when ARMv6-M code finds itself on an ARMv7-M core,
# so an unaligned access faults on the M3 as it would on the M0+ (at the cost of seven startup
# instructions more than on the M0, outside anything that is measured).
#
# The toolchain file sets LR_FW_CPU and LR_FW_BOARD (a cache entry: -DLR_FW_BOARD=... picks
# another default board at the first configure); lr_firmware_app(... BOARD b) picks one per image.
#
# For the code, every firmware target (one with the LR_BOARD property that lr_firmware_app sets)
# is compiled with LR_BOARD_RAM_SIZE=<bytes of its board's RAM region>, so that an application can
# size its stores for a small board (firmware/smoke/main.cpp does).

if(NOT LR_FW_BOARD OR NOT LR_FW_CPU)
  message(FATAL_ERROR "boards.cmake: LR_FW_BOARD and LR_FW_CPU are not set: configure with a "
                      "Cortex-M toolchain file (toolchain/cortex-m*.cmake, or a preset that names one)")
endif()

# Board table: QEMU machine; linker script (in common/); RAM region in bytes; cores whose images
# run on the board. Keep it in step with the table above and with the linker scripts.
set(_lr_board_microbit   "microbit;microbit.ld;16384;cortex-m0plus")
set(_lr_board_mps2-an385 "mps2-an385;mps2_an385.ld;4194304;cortex-m0plus")
set(_lr_board_mps2-an386 "mps2-an386;mps2_an386.ld;4194304;cortex-m4f")
set(_lr_board_mps2-an500 "mps2-an500;mps2_an500.ld;4194304;cortex-m7;cortex-m4f")
set(_lr_board_mps2-an505 "mps2-an505;mps2_an505.ld;4194304;cortex-m33")
set(LR_FW_BOARDS microbit mps2-an385 mps2-an386 mps2-an500 mps2-an505)

# The board scripts INCLUDE common/cortex_m_sections.ld, which ld looks for in its -L directories.
add_link_options(-L${CMAKE_CURRENT_LIST_DIR}/common)
# A link depends on its board script (LINK_DEPENDS, set by lr_firmware_app) but CMake does not
# know about the INCLUDEd file: startup.cpp, linked into every image and built on the symbols the
# scripts define, is recompiled when any script changes, which relinks every image.
file(GLOB _lr_linker_scripts ${CMAKE_CURRENT_LIST_DIR}/common/*.ld)
set_property(SOURCE ${CMAKE_CURRENT_LIST_DIR}/common/startup.cpp APPEND PROPERTY
             OBJECT_DEPENDS ${_lr_linker_scripts})

# LR_BOARD_RAM_SIZE for each firmware target, from its LR_BOARD property (evaluated per target
# when the build system is generated, so a BOARD given to lr_firmware_app counts).
foreach(_lr_b IN LISTS LR_FW_BOARDS)
  list(GET _lr_board_${_lr_b} 2 _lr_ram)
  add_compile_definitions(
      "$<$<STREQUAL:$<TARGET_PROPERTY:LR_BOARD>,${_lr_b}>:LR_BOARD_RAM_SIZE=${_lr_ram}>")
endforeach()

# lr_board_info(board OUT_LINKER_SCRIPT OUT_QEMU_MACHINE)
function(lr_board_info board out_ld out_machine)
  if(NOT DEFINED _lr_board_${board})
    message(FATAL_ERROR "lr_board_info: unknown board '${board}' (known: ${LR_FW_BOARDS})")
  endif()
  set(info ${_lr_board_${board}})
  list(GET info 0 machine)
  list(GET info 1 script)
  list(SUBLIST info 3 -1 cores)
  if(NOT LR_FW_CPU IN_LIST cores)
    message(FATAL_ERROR "lr_board_info: board '${board}' does not run ${LR_FW_CPU} images "
                        "(it runs: ${cores})")
  endif()
  set(${out_ld} ${CMAKE_CURRENT_FUNCTION_LIST_DIR}/common/${script} PARENT_SCOPE)
  set(${out_machine} ${machine} PARENT_SCOPE)
endfunction()

# lr_fw_boards_for_cpu(OUT_LIST): the boards that run images of this build's core (LR_FW_CPU),
# e.g. "microbit;mps2-an385" for cortex-m0plus.
function(lr_fw_boards_for_cpu out_list)
  set(boards "")
  foreach(b IN LISTS LR_FW_BOARDS)
    set(info ${_lr_board_${b}})
    list(SUBLIST info 3 -1 cores)
    if(LR_FW_CPU IN_LIST cores)
      list(APPEND boards ${b})
    endif()
  endforeach()
  set(${out_list} ${boards} PARENT_SCOPE)
endfunction()
