# The boards firmware images are linked for, each a QEMU machine.
#   mps2-an386  Cortex-M4F (the primary target); 4 MB code, 4 MB data
# The toolchain file sets LR_FW_BOARD, the board an image is for unless it names another.
if(NOT LR_FW_BOARD)
  set(LR_FW_BOARD mps2-an386)
endif()

# lr_board_info(board OUT_LINKER_SCRIPT OUT_QEMU_MACHINE)
function(lr_board_info board out_ld out_machine)
  if(board STREQUAL "mps2-an386")
    set(${out_ld} ${CMAKE_CURRENT_FUNCTION_LIST_DIR}/common/mps2_an386.ld PARENT_SCOPE)
    set(${out_machine} mps2-an386 PARENT_SCOPE)
  else()
    message(FATAL_ERROR "lr_board_info: unknown board '${board}'")
  endif()
endfunction()
