# The package: lr::core and lr::hal everywhere, lr::host (and the two programs) on hosts, as an
# exported target set with a package config and version file, so that a project uses lineraster
# by add_subdirectory, FetchContent or find_package(lineraster) with the same target names.
#
#   lr_public_library(TARGET NAME)  makes TARGET the package's lr::NAME: the alias for
#                                   add_subdirectory users, the prefixed include paths of build
#                                   and install trees, C++20 as a public compile feature.
#   lr_install()                    called once at the end of the top-level file: the install
#                                   rules, the package config and lr_package, the target that
#                                   builds everything they install.
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

# The packages whose imported targets (NAMESPACE::NAME, from find_package(NAMESPACE)) the
# libraries TARGETS link in an installation: publicly, or privately, which a static library
# passes on as $<LINK_ONLY:...> (lr::host: PNG, and JPEG when the build found it). The package
# config finds each with find_dependency before it imports the targets. They are read from the
# targets because find_package's results are local to the directory that called it (host_sim/),
# not visible here: so the config names exactly what was linked, whatever a folder adds later.
function(_lr_package_dependencies targets out)
  set(packages "")
  foreach(target IN LISTS targets)
    get_target_property(links ${target} INTERFACE_LINK_LIBRARIES)
    foreach(item IN LISTS links)
      if(item MATCHES "BUILD_INTERFACE")  # the build tree's own (lr_warnings, lr_strict)
        continue()
      endif()
      string(REGEX MATCHALL "[A-Za-z0-9_]+::" namespaces "${item}")
      foreach(namespace IN LISTS namespaces)
        string(REPLACE "::" "" package ${namespace})
        if(NOT package STREQUAL "lr")
          list(APPEND packages ${package})
        endif()
      endforeach()
    endforeach()
  endforeach()
  list(REMOVE_DUPLICATES packages)
  set(${out} "${packages}" PARENT_SCOPE)
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
  # lr_package builds what `cmake --install` installs (and what that links: lineraster-sim's
  # display backends), no tests, benchmarks or firmware: scripts/demo.sh and the `use` build
  # preset build it, so that their builds install as they are.
  if(PROJECT_IS_TOP_LEVEL)
    add_custom_target(lr_package)
    add_dependencies(lr_package ${targets} ${programs})
  endif()
  get_filename_component(root "${CMAKE_CURRENT_FUNCTION_LIST_DIR}/.." ABSOLUTE)
  set(parts core hal)
  if(TARGET lr_host)
    list(APPEND parts host_sim)
  endif()
  foreach(part IN LISTS parts)
    install(DIRECTORY ${root}/${part}/ DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/lineraster/${part}
            FILES_MATCHING PATTERN "*.hpp" PATTERN "lineraster.hpp" EXCLUDE
            PATTERN "host" EXCLUDE       # hal/host: the backends, not in the package
            PATTERN "programs" EXCLUDE)  # host_sim/programs: the two tools' own code
  endforeach()
  install(FILES ${root}/core/lineraster.hpp DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/lineraster)
  install(EXPORT lineraster-targets NAMESPACE lr:: DESTINATION ${LR_INSTALL_CMAKEDIR})
  # The host library's packages apart: the config finds them only when lr::host is wanted.
  set(base_targets ${targets})
  list(REMOVE_ITEM base_targets lr_host)
  _lr_package_dependencies("${base_targets}" LR_PACKAGE_DEPENDENCIES)
  set(LR_PACKAGE_HOST_DEPENDENCIES "")
  if(TARGET lr_host)
    _lr_package_dependencies(lr_host LR_PACKAGE_HOST_DEPENDENCIES)
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
