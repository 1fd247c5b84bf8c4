// SPDX-License-Identifier: BSD-3-Clause
#pragma once

#include <cmath>
#include <string>

#include "mpsfsi/core/abi.hpp"
#include "mpsfsi/core/detail/format.hpp"
#include "mpsfsi/core/error.hpp"
#include "mpsfsi/core/types.hpp"
#include "mpsfsi/kernels/weight.hpp"

namespace mpsfsi {
inline namespace MPSFSI_ABI {

// Constants of an MPS operator with effective radius re: the number density n0 of a full
// neighbourhood (eq 12 on the initial lattice) and the Laplacian's lambda (Koshizuka & Oka 1996)
//   lambda = sum_j w_ij |r_ij|^2 / sum_j w_ij.
// Each operator may use its own re (e.g. 2.1 l0 for density and gradient, 3.1 l0 or 4.0 l0 for
// the Laplacian), so each gets its own MpsConstants.
template <class Scalar = double>
struct MpsConstants {
  Scalar l0 = 0;
  Scalar re = 0;
  Scalar n0 = 0;
  Scalar lambda = 0;
};

// n0 and lambda summed over the square (2D) or cubic (3D) lattice of spacing l0 around one
// particle, the particle itself excluded. Throws InvalidInput unless 0 < l0 < re.
template <int Dim, class Weight, class Scalar = double>
MpsConstants<Scalar> ideal_lattice_constants(Scalar l0, Scalar re) {
  static_assert(detail::is_supported_dim<Dim>, "ideal_lattice_constants: Dim must be 2 or 3");
  check_weight<Weight>();
  if (!(l0 > 0) || !std::isfinite(l0))
    detail::throw_invalid("ideal_lattice_constants", "particle spacing l0 must be positive, got " +
                                                         detail::format_number(l0));
  if (!(re > l0) || !std::isfinite(re))
    detail::throw_invalid("ideal_lattice_constants",
                          "effective radius re must exceed l0 (re = " + detail::format_number(re) +
                              ", l0 = " + detail::format_number(l0) + ")");
  const int m = static_cast<int>(std::ceil(re / l0));
  const int mz = (Dim == 3) ? m : 0;
  Scalar n0 = 0, wr2 = 0;
  for (int a = -m; a <= m; ++a)
    for (int b = -m; b <= m; ++b)
      for (int c = -mz; c <= mz; ++c) {
        if (a == 0 && b == 0 && c == 0) continue;
        const Scalar r2 = l0 * l0 * static_cast<Scalar>(a * a + b * b + c * c);
        const Scalar w = Weight::value(std::sqrt(r2), re);
        n0 += w;
        wr2 += w * r2;
      }
  return MpsConstants<Scalar>{l0, re, n0, wr2 / n0};
}

// Particles within re (strictly closer) of one particle of the ideal lattice, itself excluded.
template <int Dim, class Scalar>
int ideal_neighbor_count(Scalar l0, Scalar re) {
  const int m = static_cast<int>(std::ceil(re / l0));
  const int mz = (Dim == 3) ? m : 0;
  int count = 0;
  for (int a = -m; a <= m; ++a)
    for (int b = -m; b <= m; ++b)
      for (int c = -mz; c <= mz; ++c)
        if ((a != 0 || b != 0 || c != 0) && l0 * std::sqrt(static_cast<Scalar>(a * a + b * b + c * c)) < re) ++count;
  return count;
}

}  // namespace MPSFSI_ABI
}  // namespace mpsfsi
