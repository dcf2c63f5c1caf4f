# Finds the OpenNN 0.56.2 shared library built by scripts/build-opennn.sh and defines the imported target OpenNN::opennn.
# Hints: CLOTHCD_OPENNN_ROOT or OpenNN_ROOT (the install prefix).
find_path(OpenNN_INCLUDE_DIR opennn/opennn.h HINTS ${CLOTHCD_OPENNN_ROOT} ${OpenNN_ROOT} PATH_SUFFIXES include)
find_library(OpenNN_LIBRARY opennn HINTS ${CLOTHCD_OPENNN_ROOT} ${OpenNN_ROOT} PATH_SUFFIXES lib)

include(FindPackageHandleStandardArgs)
find_package_handle_standard_args(OpenNN
  REQUIRED_VARS OpenNN_LIBRARY OpenNN_INCLUDE_DIR
  REASON_FAILURE_MESSAGE "run scripts/build-opennn.sh first (it downloads and builds OpenNN 0.56.2)")

if(OpenNN_FOUND AND NOT TARGET OpenNN::opennn)
  find_package(Eigen3 3.4 REQUIRED NO_MODULE)
  add_library(OpenNN::opennn SHARED IMPORTED)
  set_target_properties(OpenNN::opennn PROPERTIES
    IMPORTED_LOCATION "${OpenNN_LIBRARY}"
    INTERFACE_INCLUDE_DIRECTORIES "${OpenNN_INCLUDE_DIR}"
    INTERFACE_LINK_LIBRARIES Eigen3::Eigen)
endif()
