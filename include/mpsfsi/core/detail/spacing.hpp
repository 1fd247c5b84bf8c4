// SPDX-License-Identifier: BSD-3-Clause
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <string>
#include <vector>

#include "mpsfsi/core/abi.hpp"
#include "mpsfsi/core/detail/format.hpp"
#include "mpsfsi/core/error.hpp"

namespace mpsfsi {
inline namespace MPSFSI_ABI {
namespace detail {

// Throws InvalidInput when the particles' spacing disagrees with l0. The mass rho l0^d and the
// lattice constants n0 and lambda (docs/theory.md, section 1.2) assume particles l0 apart; the
// spacing is the median of `nearest` (each particle's distance to its nearest neighbour, exactly
// l0 on a lattice). 10 % off already puts the mass, or the number density against n0, 21 % (2D)
// or 33 % (3D) off. Reorders `nearest`.
inline void check_median_spacing(std::vector<double>& nearest, double l0, const std::string& who) {
  if (nearest.empty()) return;
  const auto middle = nearest.begin() + static_cast<std::ptrdiff_t>(nearest.size() / 2);
  std::nth_element(nearest.begin(), middle, nearest.end());
  const double spacing = *middle;
  if (std::abs(spacing / l0 - 1) > 0.1)
    throw_invalid(who, "the particles are " + format_number(spacing) +
                           " m apart (median distance to the nearest neighbour) but l0 = " + format_number(l0) +
                           " m: build them l0 apart or set l0 to their spacing");
}

}  // namespace detail
}  // namespace MPSFSI_ABI
}  // namespace mpsfsi
