# The package: lr::core and lr::hal everywhere, lr::host (and the two programs) on hosts, as an
# exported target set with a package config and version file, so that a project uses lineraster
# by add_subdirectory, FetchContent or find_package(lineraster) with the same target names.
#
#   lr_public_library(TARGET NAME)  makes TARGET the package's lr::NAME: the alias for
#                                   add_subdirectory users, the prefixed include paths of build
#                                   and install trees, C++20 as a public compile feature.
#   lr_install()                    called once at the end of the top-level file.
include_guard(GLOBAL)
include(GNUInstallDirs)
include(CMakePackageConfigHelpers)
include(${CMAKE_CURRENT_LIST_DIR}/include_view.cmake)

set(LR_INSTALL_CMAKEDIR "${CMAKE_INSTALL_LIBDIR}/cmake/lineraster")

function(lr_public_library target name)
  add_library(lr::${name} ALIAS ${target})
  set_target_properties(${target} PROPERTIES EXPORT_NAME ${name} OUTPUT_NAME lineraster_${name})
  target_include_directories(${target} PUBLIC $<BUILD_INTERFACE:${LR_INCLUDE_VIEW}>
                                              $<INSTALL_INTERFACE:${CMAKE_INSTALL_INCLUDEDIR}>)
  target_compile_features(${target} PUBLIC cxx_std_20)
  set_property(GLOBAL APPEND PROPERTY LR_PUBLIC_LIBRARIES ${target})
endfunction()

function(lr_install)
  get_property(targets GLOBAL PROPERTY LR_PUBLIC_LIBRARIES)
  set(programs "")
  foreach(p lineraster-sim lineraster-asset)
    if(TARGET ${p})
      list(APPEND programs ${p})
    endif()
  endforeach()
  install(TARGETS ${targets} ${programs} EXPORT lineraster-targets
          ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
          RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
  get_filename_component(root "${CMAKE_CURRENT_FUNCTION_LIST_DIR}/.." ABSOLUTE)
  set(parts core hal)
  if(TARGET lr_host)
    list(APPEND parts host_sim)
  endif()
  foreach(part IN LISTS parts)
    install(DIRECTORY ${root}/${part}/ DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/lineraster/${part}
            FILES_MATCHING PATTERN "*.hpp" PATTERN "lineraster.hpp" EXCLUDE
            PATTERN "host" EXCLUDE)  # hal/host: the backends, not in the package
  endforeach()
  install(FILES ${root}/core/lineraster.hpp DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/lineraster)
  install(EXPORT lineraster-targets NAMESPACE lr:: DESTINATION ${LR_INSTALL_CMAKEDIR})
  if(TARGET lr_host)
    set(LR_PACKAGE_HOST ON)
  else()
    set(LR_PACKAGE_HOST OFF)
  endif()
  if(LR_PACKAGE_HOST AND JPEG_FOUND)
    set(LR_PACKAGE_JPEG ON)
  else()
    set(LR_PACKAGE_JPEG OFF)
  endif()
  configure_package_config_file(${CMAKE_CURRENT_FUNCTION_LIST_DIR}/lineraster-config.cmake.in
    ${PROJECT_BINARY_DIR}/lineraster-config.cmake INSTALL_DESTINATION ${LR_INSTALL_CMAKEDIR})
  # 0.x: a minor version may change the API, so only the same minor version is compatible.
  write_basic_package_version_file(${PROJECT_BINARY_DIR}/lineraster-config-version.cmake
    COMPATIBILITY SameMinorVersion)
  install(FILES ${PROJECT_BINARY_DIR}/lineraster-config.cmake
                ${PROJECT_BINARY_DIR}/lineraster-config-version.cmake
          DESTINATION ${LR_INSTALL_CMAKEDIR})
endfunction()
