// SPDX-License-Identifier: BSD-3-Clause
#pragma once

#include <algorithm>
#include <cmath>

namespace mpsfsi::test {

// |value - reference| <= tolerance * |reference|: the relative tolerance a verification test
// states, taken literally (doctest's Approx adds its own scale and is about twice as loose).
inline bool within_relative(double value, double reference, double tolerance) {
  return std::abs(value - reference) <= tolerance * std::abs(reference);
}

}  // namespace mpsfsi::test
