# Relocatable CMake package: find_package(isodel) then link isodel::isodel.
include(GNUInstallDirs)
include(CMakePackageConfigHelpers)
install(TARGETS isodel isodel_verify isodel_octree EXPORT isodelTargets
  ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
  LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
  RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
if(TARGET isodel_cli)
  install(TARGETS isodel_cli RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
endif()
install(DIRECTORY include/isodel DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
install(EXPORT isodelTargets NAMESPACE isodel:: DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/isodel)
configure_package_config_file(cmake/isodelConfig.cmake.in
  ${PROJECT_BINARY_DIR}/isodelConfig.cmake
  INSTALL_DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/isodel)
write_basic_package_version_file(${PROJECT_BINARY_DIR}/isodelConfigVersion.cmake
  COMPATIBILITY SameMinorVersion)
install(FILES ${PROJECT_BINARY_DIR}/isodelConfig.cmake ${PROJECT_BINARY_DIR}/isodelConfigVersion.cmake
  DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/isodel)
