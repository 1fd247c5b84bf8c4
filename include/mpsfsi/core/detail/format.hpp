// SPDX-License-Identifier: BSD-3-Clause
#pragma once

#include <cstdio>
#include <string>

#include "mpsfsi/core/abi.hpp"

namespace mpsfsi {
inline namespace MPSFSI_ABI {
namespace detail {

// A number for an error or log message with six significant digits ("4.3e-07", "0.0125",
// "1.2e+06"): std::to_string's fixed six decimals would print a 4.3e-7 s time step as 0.000000.
inline std::string format_number(double value) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.6g", value);
  return buffer;
}

}  // namespace detail
}  // namespace MPSFSI_ABI
}  // namespace mpsfsi
