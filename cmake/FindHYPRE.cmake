# SPDX-License-Identifier: BSD-3-Clause
# Finds hypre (e.g. Debian's libhypre-dev, which ships no CMake files) and the MPI it is built
# with, and provides HYPRE::HYPRE. Sets HYPRE_FOUND, HYPRE_INCLUDE_DIR, HYPRE_LIBRARY, HYPRE_VERSION.

if(TARGET HYPRE::HYPRE)
  set(HYPRE_FOUND TRUE)
  return()
endif()

find_path(HYPRE_INCLUDE_DIR NAMES HYPRE.h PATH_SUFFIXES hypre)
find_library(HYPRE_LIBRARY NAMES HYPRE)
if(HYPRE_INCLUDE_DIR AND EXISTS "${HYPRE_INCLUDE_DIR}/HYPRE_config.h")
  file(STRINGS "${HYPRE_INCLUDE_DIR}/HYPRE_config.h" _hypre_version_line REGEX "#define HYPRE_RELEASE_VERSION")
  string(REGEX MATCH "[0-9]+\\.[0-9]+\\.[0-9]+" HYPRE_VERSION "${_hypre_version_line}")
  file(STRINGS "${HYPRE_INCLUDE_DIR}/HYPRE_config.h" _hypre_mpi REGEX "#define HYPRE_HAVE_MPI 1")
endif()
set(_hypre_extra_vars "")
# hypre's headers include mpi.h; the MPI component follows the languages enabled (FindMPI's C
# component needs the C language, which a C++-only project does not enable).
if(_hypre_mpi)
  if(CMAKE_CXX_COMPILER_LOADED)
    set(_hypre_mpi_lang CXX)
  else()
    set(_hypre_mpi_lang C)
  endif()
  find_package(MPI COMPONENTS ${_hypre_mpi_lang} QUIET)
  set(_hypre_extra_vars MPI_${_hypre_mpi_lang}_FOUND)
endif()

include(FindPackageHandleStandardArgs)
find_package_handle_standard_args(HYPRE
  REQUIRED_VARS HYPRE_LIBRARY HYPRE_INCLUDE_DIR ${_hypre_extra_vars}
  VERSION_VAR HYPRE_VERSION)

if(HYPRE_FOUND AND NOT TARGET HYPRE::HYPRE)
  add_library(HYPRE::HYPRE INTERFACE IMPORTED)
  set_target_properties(HYPRE::HYPRE PROPERTIES
    INTERFACE_INCLUDE_DIRECTORIES "${HYPRE_INCLUDE_DIR}"
    INTERFACE_LINK_LIBRARIES "${HYPRE_LIBRARY}")
  if(_hypre_mpi)
    set_property(TARGET HYPRE::HYPRE APPEND PROPERTY INTERFACE_LINK_LIBRARIES MPI::MPI_${_hypre_mpi_lang})
  endif()
endif()
mark_as_advanced(HYPRE_INCLUDE_DIR HYPRE_LIBRARY)
