# SPDX-License-Identifier: BSD-3-Clause
# Finds nanoflann and provides nanoflann::nanoflann: a target that already exists (e.g. from a
# parent project), else nanoflann's own CMake package, else the bare header with an imported
# target made for it (installations that ship no CMake files).
# Sets nanoflann_FOUND, nanoflann_VERSION and nanoflann_INCLUDE_DIR.

if(TARGET nanoflann::nanoflann)
  set(nanoflann_FOUND TRUE)
  return()
endif()

find_package(nanoflann ${nanoflann_FIND_VERSION} CONFIG QUIET)
if(nanoflann_FOUND AND TARGET nanoflann::nanoflann)
  return()
endif()

find_path(nanoflann_INCLUDE_DIR NAMES nanoflann.hpp)
if(nanoflann_INCLUDE_DIR)
  file(STRINGS "${nanoflann_INCLUDE_DIR}/nanoflann.hpp" _nanoflann_version_line
       REGEX "#define NANOFLANN_VERSION 0x[0-9A-Fa-f]+")
  string(REGEX MATCH "0x([0-9A-Fa-f])([0-9A-Fa-f])([0-9A-Fa-f])" _m "${_nanoflann_version_line}")
  if(_m)
    set(nanoflann_VERSION "${CMAKE_MATCH_1}.${CMAKE_MATCH_2}.${CMAKE_MATCH_3}")
  endif()
endif()

include(FindPackageHandleStandardArgs)
find_package_handle_standard_args(nanoflann
  REQUIRED_VARS nanoflann_INCLUDE_DIR
  VERSION_VAR nanoflann_VERSION)

if(nanoflann_FOUND AND NOT TARGET nanoflann::nanoflann)
  add_library(nanoflann::nanoflann INTERFACE IMPORTED)
  set_target_properties(nanoflann::nanoflann PROPERTIES
    INTERFACE_INCLUDE_DIRECTORIES "${nanoflann_INCLUDE_DIR}")
endif()
mark_as_advanced(nanoflann_INCLUDE_DIR)
