# Installs the libraries, their headers, the default model and a package config so that find_package(clothcd) works
# from the install prefix, wherever the prefix is moved: every path is relative, the libraries find each other (and
# OpenNN's, copied beside clothcd::learning) through an $ORIGIN run path.
include(CMakePackageConfigHelpers)

set(clothcd_installed_targets clothcd_core clothcd)
if(CLOTHCD_LEARNING)
  list(APPEND clothcd_installed_targets clothcd_learning)
  # OpenNN is no Debian package: its shared library (LGPL) goes beside clothcd's, under its SONAME.
  install(FILES ${OpenNN_LIBRARY} DESTINATION ${CMAKE_INSTALL_LIBDIR})
endif()
install(TARGETS ${clothcd_installed_targets} EXPORT clothcdTargets
  LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
  ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
  RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR}
  INCLUDES DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
install(DIRECTORY include/clothcd DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
install(FILES ${PROJECT_BINARY_DIR}/include/clothcd/version.hpp DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/clothcd)
install(DIRECTORY models/default DESTINATION ${CMAKE_INSTALL_DATADIR}/clothcd/models FILES_MATCHING PATTERN "*.xml" PATTERN "*.json")
install(FILES LICENSE THIRD_PARTY_NOTICES.md DESTINATION ${CMAKE_INSTALL_DATADIR}/doc/clothcd)
if(CLOTHCD_BUILD_TOOLS)
  install(TARGETS clothcd_cli RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
endif()

set(config_dir ${CMAKE_INSTALL_LIBDIR}/cmake/clothcd)
install(EXPORT clothcdTargets NAMESPACE clothcd:: DESTINATION ${config_dir})
# The libraries are shared and link their dependencies privately: a consumer needs Eigen only (public types).
get_target_property(clothcd_core_type clothcd_core TYPE)
if(NOT clothcd_core_type STREQUAL "SHARED_LIBRARY")
  message(FATAL_ERROR "installing clothcd needs BUILD_SHARED_LIBS=ON (or CLOTHCD_INSTALL=OFF)")
endif()
configure_package_config_file(cmake/clothcdConfig.cmake.in ${CMAKE_CURRENT_BINARY_DIR}/clothcdConfig.cmake
  INSTALL_DESTINATION ${config_dir})
write_basic_package_version_file(${CMAKE_CURRENT_BINARY_DIR}/clothcdConfigVersion.cmake COMPATIBILITY SameMinorVersion)
install(FILES ${CMAKE_CURRENT_BINARY_DIR}/clothcdConfig.cmake ${CMAKE_CURRENT_BINARY_DIR}/clothcdConfigVersion.cmake
  DESTINATION ${config_dir})
