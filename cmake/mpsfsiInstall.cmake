# SPDX-License-Identifier: BSD-3-Clause
# Install rules and the exported CMake package: find_package(mpsfsi 0.1 REQUIRED).
include(CMakePackageConfigHelpers)

set(MPSFSI_INSTALL_CMAKEDIR "${CMAKE_INSTALL_DATADIR}/cmake/mpsfsi" CACHE STRING
    "Where mpsfsiConfig.cmake is installed (the package is architecture independent)")

install(TARGETS mpsfsi EXPORT mpsfsiTargets)
install(DIRECTORY include/ DESTINATION "${CMAKE_INSTALL_INCLUDEDIR}" FILES_MATCHING PATTERN "*.hpp")
install(EXPORT mpsfsiTargets NAMESPACE mpsfsi:: DESTINATION "${MPSFSI_INSTALL_CMAKEDIR}")
if(MPSFSI_WITH_HYPRE)
  install(TARGETS mpsfsi_hypre EXPORT mpsfsiHypreTargets)
  install(EXPORT mpsfsiHypreTargets NAMESPACE mpsfsi:: DESTINATION "${MPSFSI_INSTALL_CMAKEDIR}")
  install(FILES cmake/FindHYPRE.cmake DESTINATION "${MPSFSI_INSTALL_CMAKEDIR}")
endif()
if(MPSFSI_WITH_MPI)
  install(TARGETS mpsfsi_mpi EXPORT mpsfsiMpiTargets)
  install(EXPORT mpsfsiMpiTargets NAMESPACE mpsfsi:: DESTINATION "${MPSFSI_INSTALL_CMAKEDIR}")
endif()

configure_package_config_file(cmake/mpsfsiConfig.cmake.in
  "${PROJECT_BINARY_DIR}/mpsfsiConfig.cmake"
  INSTALL_DESTINATION "${MPSFSI_INSTALL_CMAKEDIR}")
write_basic_package_version_file("${PROJECT_BINARY_DIR}/mpsfsiConfigVersion.cmake"
  COMPATIBILITY SameMinorVersion ARCH_INDEPENDENT)
install(FILES
  "${PROJECT_BINARY_DIR}/mpsfsiConfig.cmake"
  "${PROJECT_BINARY_DIR}/mpsfsiConfigVersion.cmake"
  cmake/Findnanoflann.cmake
  DESTINATION "${MPSFSI_INSTALL_CMAKEDIR}")

# Build-tree export, so a consumer can point mpsfsi_DIR at a build directory without installing.
export(EXPORT mpsfsiTargets NAMESPACE mpsfsi:: FILE "${PROJECT_BINARY_DIR}/mpsfsiTargets.cmake")
configure_file(cmake/Findnanoflann.cmake "${PROJECT_BINARY_DIR}/Findnanoflann.cmake" COPYONLY)
