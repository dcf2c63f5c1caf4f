# Installs the library, its headers and a package config so that find_package(clothcd) works from the install prefix.
include(CMakePackageConfigHelpers)

install(TARGETS clothcd EXPORT clothcdTargets
  LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
  ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
  RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR}
  INCLUDES DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
install(DIRECTORY include/clothcd DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
install(DIRECTORY models/default DESTINATION ${CMAKE_INSTALL_DATADIR}/clothcd/models FILES_MATCHING PATTERN "*.xml" PATTERN "*.json")
if(CLOTHCD_BUILD_TOOLS)
  install(TARGETS clothcd_cli RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
endif()

set(config_dir ${CMAKE_INSTALL_LIBDIR}/cmake/clothcd)
install(EXPORT clothcdTargets NAMESPACE clothcd:: DESTINATION ${config_dir})
configure_package_config_file(cmake/clothcdConfig.cmake.in ${CMAKE_CURRENT_BINARY_DIR}/clothcdConfig.cmake
  INSTALL_DESTINATION ${config_dir})
write_basic_package_version_file(${CMAKE_CURRENT_BINARY_DIR}/clothcdConfigVersion.cmake COMPATIBILITY SameMinorVersion)
install(FILES ${CMAKE_CURRENT_BINARY_DIR}/clothcdConfig.cmake ${CMAKE_CURRENT_BINARY_DIR}/clothcdConfigVersion.cmake
  cmake/FindOpenNN.cmake DESTINATION ${config_dir})
