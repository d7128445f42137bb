# The library's include paths carry the project prefix: <lineraster/core/...>, <lineraster/hal/...>,
# <lineraster/host_sim/...> and the core's umbrella <lineraster/lineraster.hpp>. The sources stay
# in their pipeline folders; a build sees them through a view in its binary directory whose only
# entry is lineraster/, so a consumer's include path never holds the repository root (and its
# own core/ or hal/ cannot collide with ours). Installed headers are laid out the same way
# (cmake/install.cmake).
#
# Sets LR_INCLUDE_VIEW: the directory to put on include paths (BUILD_INTERFACE).
# Symbolic links where the file system has them; elsewhere (Windows without the privilege) a
# copy of the headers, made at configure time.
include_guard(GLOBAL)

get_filename_component(_lr_view_root "${CMAKE_CURRENT_LIST_DIR}/.." ABSOLUTE)
set(LR_INCLUDE_VIEW "${CMAKE_BINARY_DIR}/lr_include")
file(MAKE_DIRECTORY "${LR_INCLUDE_VIEW}/lineraster")

function(_lr_view_link source name)
  set(link "${LR_INCLUDE_VIEW}/lineraster/${name}")
  if(IS_SYMLINK "${link}")
    file(READ_SYMLINK "${link}" current)
    if(current STREQUAL source)
      return()
    endif()
  endif()
  file(REMOVE_RECURSE "${link}")
  file(CREATE_LINK "${source}" "${link}" SYMBOLIC RESULT failed)
  if(failed)
    if(IS_DIRECTORY "${source}")
      file(COPY "${source}/" DESTINATION "${link}" FILES_MATCHING PATTERN "*.hpp")
    else()
      file(COPY_FILE "${source}" "${link}")
    endif()
    message(STATUS "lineraster: ${name} copied into the include view (no symbolic links here)")
  endif()
endfunction()

foreach(_lr_part core hal host_sim)
  _lr_view_link("${_lr_view_root}/${_lr_part}" "${_lr_part}")
endforeach()
_lr_view_link("${_lr_view_root}/core/lineraster.hpp" "lineraster.hpp")
