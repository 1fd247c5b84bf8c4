// SPDX-License-Identifier: BSD-3-Clause
#pragma once

#include <algorithm>
#include <cmath>
#include <type_traits>
#include <utility>

#include "mpsfsi/core/abi.hpp"

namespace mpsfsi {
inline namespace MPSFSI_ABI {

// A weight policy is a type with `static Scalar value(Scalar r, Scalar re)`, zero for r >= re.
// Operators take it as a template argument: number_density<KoshizukaWeight>(...).

// The weight function of Koshizuka & Oka 1996, the paper's eq 13: w(r) = re/r - 1 for r < re.
// It is singular at r -> 0; distances below `min_distance_ratio * re` are treated as that
// distance, which bounds w by 1/min_distance_ratio - 1 (= 99) for coincident particles.
struct KoshizukaWeight {
  static constexpr double min_distance_ratio = 0.01;

  template <class Scalar>
  static Scalar value(Scalar r, Scalar re) {
    if (!(r < re)) return Scalar(0);
    return re / std::max(r, static_cast<Scalar>(min_distance_ratio) * re) - Scalar(1);
  }
};

// A smooth, non-singular alternative: the Wendland C2 function w = (1 - q)^4 (1 + 4q),
// q = r/re, bounded by 1 at r = 0 and with zero value and slope at re.
struct WendlandC2Weight {
  template <class Scalar>
  static Scalar value(Scalar r, Scalar re) {
    if (!(r < re)) return Scalar(0);
    const Scalar q = r / re;
    const Scalar a = Scalar(1) - q;
    const Scalar a2 = a * a;
    return a2 * a2 * (Scalar(1) + Scalar(4) * q);
  }
};

namespace detail {

template <class W, class = void>
struct is_weight : std::false_type {};
template <class W>
struct is_weight<W, std::void_t<decltype(W::value(std::declval<double>(), std::declval<double>()))>>
    : std::true_type {};

}  // namespace detail

template <class W>
constexpr bool check_weight() {
  static_assert(detail::is_weight<W>::value,
                "weight policy lacks `static Scalar value(Scalar r, Scalar re)`");
  return true;
}

}  // namespace MPSFSI_ABI
}  // namespace mpsfsi
