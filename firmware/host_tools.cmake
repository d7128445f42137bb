# lineraster-asset for cross builds: the converter runs on the build machine, so a bare-metal
# tree cannot build it with its own (Arm) compiler. Either point LR_HOST_TOOLS_DIR at a host
# build tree that has built it (CI passes build/release), or let this file build it, once for
# every cross tree, in build/host-tools with the build machine's compiler (ExternalProject: a
# separate CMake run of this project with LR_HOST=ON and no tests; it needs libpng, as the
# converter reads PNG textures).
#
# In a host build tree the converter is simply this project's own target.
#
# Defines LR_ASSET_TOOL (the program) and LR_ASSET_TOOL_TARGET (a target to depend on, or "").
include_guard(GLOBAL)
set(LR_HOST_TOOLS_DIR "" CACHE PATH
    "Host build tree with host_sim/lineraster-asset built (empty: build it in build/host-tools)")

if(NOT CMAKE_CROSSCOMPILING AND TARGET lineraster-asset)
  set(LR_ASSET_TOOL $<TARGET_FILE:lineraster-asset>)
  set(LR_ASSET_TOOL_TARGET lineraster-asset)
elseif(LR_HOST_TOOLS_DIR)
  set(LR_ASSET_TOOL ${LR_HOST_TOOLS_DIR}/host_sim/lineraster-asset)
  if(NOT EXISTS ${LR_ASSET_TOOL})
    message(FATAL_ERROR "LR_HOST_TOOLS_DIR=${LR_HOST_TOOLS_DIR}: ${LR_ASSET_TOOL} does not exist "
                        "(build it: cmake --build ${LR_HOST_TOOLS_DIR} --target lineraster-asset)")
  endif()
  set(LR_ASSET_TOOL_TARGET "")
else()
  include(ExternalProject)
  set(_lr_host_tools_bin ${PROJECT_SOURCE_DIR}/build/host-tools)
  ExternalProject_Add(lr_host_tools
    SOURCE_DIR ${PROJECT_SOURCE_DIR}
    BINARY_DIR ${_lr_host_tools_bin}
    # No toolchain file: the build machine's compiler. Only the converter is built.
    CMAKE_ARGS -DCMAKE_BUILD_TYPE=Release -DLR_HOST=ON -DLR_TESTS=OFF -DLR_BENCH=OFF
               -DLR_DISPLAY_BACKENDS=OFF
    BUILD_COMMAND ${CMAKE_COMMAND} --build ${_lr_host_tools_bin} --target lineraster-asset
    BUILD_BYPRODUCTS ${_lr_host_tools_bin}/host_sim/lineraster-asset
    INSTALL_COMMAND ""
    BUILD_ALWAYS ON)
  set(LR_ASSET_TOOL ${_lr_host_tools_bin}/host_sim/lineraster-asset)
  set(LR_ASSET_TOOL_TARGET lr_host_tools)
endif()

# lr_asset_header(NAME OBJ [converter options...]): generates ${CMAKE_CURRENT_BINARY_DIR}/
# generated/NAME.hpp (namespace NAME) from OBJ (relative to the source tree) at build time;
# the variable NAME_HEADER holds its path.
function(lr_asset_header name obj)
  set(out ${CMAKE_CURRENT_BINARY_DIR}/generated/${name}.hpp)
  add_custom_command(
    OUTPUT ${out}
    COMMAND ${CMAKE_COMMAND} -E make_directory ${CMAKE_CURRENT_BINARY_DIR}/generated
    COMMAND ${LR_ASSET_TOOL} --obj ${PROJECT_SOURCE_DIR}/${obj} ${ARGN} --name ${name} --out ${out}
    DEPENDS ${PROJECT_SOURCE_DIR}/${obj} ${LR_ASSET_TOOL_TARGET}
    WORKING_DIRECTORY ${PROJECT_SOURCE_DIR}
    COMMENT "lineraster-asset: ${obj} -> ${name}.hpp"
    VERBATIM)
  set(${name}_HEADER ${out} PARENT_SCOPE)
endfunction()
