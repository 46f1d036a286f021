
include(CMakePackageConfigHelpers)
# Installed as sfit::sfit and sfit::io, the names the build tree uses too.
set_target_properties(sfit_io PROPERTIES EXPORT_NAME io)
install(TARGETS sfit sfit_io EXPORT sfitTargets
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
        LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
        RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR}
        INCLUDES DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
install(DIRECTORY include/sfit DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
install(TARGETS sfit_cli RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
install(EXPORT sfitTargets NAMESPACE sfit:: DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/sfit)
configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/sfitConfig.cmake.in
  ${PROJECT_BINARY_DIR}/sfitConfig.cmake INSTALL_DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/sfit)
write_basic_package_version_file(${PROJECT_BINARY_DIR}/sfitConfigVersion.cmake
  COMPATIBILITY SameMinorVersion)
install(FILES ${PROJECT_BINARY_DIR}/sfitConfig.cmake ${PROJECT_BINARY_DIR}/sfitConfigVersion.cmake
        DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/sfit)
