// SPDX-License-Identifier: BSD-3-Clause
#pragma once

#include "mpsfsi/core/abi.hpp"

// The one version string of mpsfsi; CMakeLists.txt reads these three lines.
#define MPSFSI_VERSION_MAJOR 0
#define MPSFSI_VERSION_MINOR 1
#define MPSFSI_VERSION_PATCH 0

#define MPSFSI_VERSION_STRING "0.1.0"

namespace mpsfsi {
inline namespace MPSFSI_ABI {
inline constexpr int version_major = MPSFSI_VERSION_MAJOR;
inline constexpr int version_minor = MPSFSI_VERSION_MINOR;
inline constexpr int version_patch = MPSFSI_VERSION_PATCH;
inline constexpr const char* version_string = MPSFSI_VERSION_STRING;
}  // namespace MPSFSI_ABI
}  // namespace mpsfsi
