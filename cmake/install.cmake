# Installation, the CMake package and the Debian package (CPack).
#   find_package(sfit REQUIRED [COMPONENTS render exchange])
#   sfit::sfit (core) and sfit::io always; sfit::render with the component render;
#   sfit::mesh and sfit::exchange with the component exchange.
include(CMakePackageConfigHelpers)
set(SFIT_CMAKE_DIR ${CMAKE_INSTALL_LIBDIR}/cmake/sfit)

set(_sfit_libs sfit sfit_io sfit_render sfit_mesh sfit_exchange)
foreach(_lib IN LISTS _sfit_libs)
  if(TARGET ${_lib})
    set_target_properties(${_lib} PROPERTIES
      VERSION ${PROJECT_VERSION} SOVERSION ${PROJECT_VERSION_MAJOR}.${PROJECT_VERSION_MINOR})
  endif()
endforeach()
set(_sfit_destinations
    ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
    LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
    RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR}
    INCLUDES DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})

# The core and io: always. Headers: every one of include/sfit/ and include/sfit/io/, and the
# generated version.h.
set_target_properties(sfit_io PROPERTIES EXPORT_NAME io)
install(TARGETS sfit sfit_io EXPORT sfitTargets ${_sfit_destinations})
install(DIRECTORY include/sfit DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}
        PATTERN render EXCLUDE PATTERN exchange EXCLUDE
        PATTERN files.h EXCLUDE)  # sfit_files: the CLI's and Python's, not installed
install(FILES ${PROJECT_BINARY_DIR}/include/sfit/version.h
        DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/sfit)
install(EXPORT sfitTargets NAMESPACE sfit:: DESTINATION ${SFIT_CMAKE_DIR})
install(TARGETS sfit_cli RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})

# The optional components, each with its headers and its own export file.
set(SFIT_COMPONENTS "")
if(TARGET sfit_render)
  list(APPEND SFIT_COMPONENTS render)
  set_target_properties(sfit_render PROPERTIES EXPORT_NAME render)
  install(TARGETS sfit_render EXPORT sfitRenderTargets ${_sfit_destinations})
  install(DIRECTORY include/sfit/render DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/sfit)
  install(EXPORT sfitRenderTargets NAMESPACE sfit:: DESTINATION ${SFIT_CMAKE_DIR})
endif()
if(TARGET sfit_exchange)
  list(APPEND SFIT_COMPONENTS exchange)
  set_target_properties(sfit_mesh PROPERTIES EXPORT_NAME mesh)
  set_target_properties(sfit_exchange PROPERTIES EXPORT_NAME exchange)
  install(TARGETS sfit_mesh sfit_exchange EXPORT sfitExchangeTargets ${_sfit_destinations})
  install(DIRECTORY include/sfit/exchange DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/sfit)
  install(EXPORT sfitExchangeTargets NAMESPACE sfit:: DESTINATION ${SFIT_CMAKE_DIR})
endif()
if(TARGET sfit_cad)  # STEP/IGES, loaded by sfit_exchange on first use (src/exchange/cad_module.h)
  install(TARGETS sfit_cad LIBRARY DESTINATION ${SFIT_CAD_INSTALL_DIR})
endif()

# What the package config must find again: private dependencies of static libraries are part
# of their link interface.
set(SFIT_STATIC_RENDER_DEPS "")
set(SFIT_STATIC_EXCHANGE_DEPS "")
if(NOT BUILD_SHARED_LIBS)
  set(SFIT_STATIC_RENDER_DEPS "find_dependency(PNG)")
endif()
configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/sfitConfig.cmake.in
  ${PROJECT_BINARY_DIR}/sfitConfig.cmake INSTALL_DESTINATION ${SFIT_CMAKE_DIR})
write_basic_package_version_file(${PROJECT_BINARY_DIR}/sfitConfigVersion.cmake
  COMPATIBILITY SameMinorVersion)
install(FILES ${PROJECT_BINARY_DIR}/sfitConfig.cmake ${PROJECT_BINARY_DIR}/sfitConfigVersion.cmake
        DESTINATION ${SFIT_CMAKE_DIR})

# The Debian package: cmake --build build --target package  ->  build/sfit_VERSION_ARCH.deb
# with the CLI, the libraries, the headers and the CMake package, installed under /usr; where
# the Python module is built, also the module and the FreeCAD workbench (docs/freecad.md).
set(CPACK_GENERATOR DEB)
set(CPACK_PACKAGE_NAME sfit)
set(CPACK_PACKAGE_VENDOR "the sfit developers")
set(CPACK_PACKAGE_DESCRIPTION_SUMMARY "${PROJECT_DESCRIPTION}")
set(CPACK_PACKAGE_VERSION ${PROJECT_VERSION})
set(CPACK_RESOURCE_FILE_LICENSE ${PROJECT_SOURCE_DIR}/LICENSE)
set(CPACK_PACKAGING_INSTALL_PREFIX /usr)
set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)
set(CPACK_DEBIAN_PACKAGE_MAINTAINER "the sfit developers")
set(CPACK_DEBIAN_PACKAGE_SECTION science)
# Consumers of the headers and the CMake package need Eigen and nlohmann-json; the parts that
# are on need their libraries (the -dev packages, for a static build's link interface too).
set(_sfit_depends "libeigen3-dev, nlohmann-json3-dev, libfmt-dev")
if(TARGET sfit_render)
  string(APPEND _sfit_depends ", libpng-dev")
endif()
if(SFIT_EXCHANGE_CAD)
  string(APPEND _sfit_depends ", libocct-foundation-dev, libocct-modeling-data-dev"
         ", libocct-modeling-algorithms-dev, libocct-data-exchange-dev, libtbb-dev")
endif()
if(TARGET sfit_python)  # the Python module and the FreeCAD workbench that imports it
  string(APPEND _sfit_depends ", python3, python3-numpy")
  set(CPACK_DEBIAN_PACKAGE_SUGGESTS "freecad")
endif()
set(CPACK_DEBIAN_PACKAGE_DEPENDS "${_sfit_depends}")
include(CPack)
