// SPDX-License-Identifier: BSD-3-Clause
#pragma once

#include <algorithm>
#include <cstdint>
#include <vector>

#include "mpsfsi/core/abi.hpp"
#include "mpsfsi/core/neighbor_list.hpp"
#include "mpsfsi/core/parallel.hpp"
#include "mpsfsi/core/types.hpp"
#include "mpsfsi/kernels/detail/pair.hpp"
#include "mpsfsi/kernels/lattice_constants.hpp"
#include "mpsfsi/kernels/weight.hpp"

namespace mpsfsi {
inline namespace MPSFSI_ABI {

// Which value phi_j is compared with in the gradient sum.
enum class GradientReference {
  own_value,          // phi_i: exact for linear fields (with correction, on any arrangement)
  neighbour_minimum,  // phi_hat_i = min(phi_i, min_j phi_j): Koshizuka & Oka's stabilised
                      // pressure gradient, repulsive between every pair
};

// MPS gradient of a scalar field with a correction policy (gradient_correction.hpp):
//   <grad phi>_i = (1/n0) sum_j (phi_j - phi_ref) / |r_ij|^2 w_ij C_i r_ij,
// with C_i = d I for NoGradientCorrection (the standard operator) and C_i = A_i^-1 for
// KhayyerGotohCorrection (eq 14's GC pressure gradient). The correction must be up to date.
template <class Weight, int Dim, class Scalar, class Correction>
void gradient(const VecArray<Dim, Scalar>& x, const BasicNeighborList<Scalar>& list,
              const std::vector<Scalar>& phi, const MpsConstants<Scalar>& c, const Correction& correction,
              VecArray<Dim, Scalar>& grad, GradientReference reference = GradientReference::own_value) {
  check_weight<Weight>();
  detail::require_list_rows(list, x.size(), "gradient");
  detail::require_same_size(x, phi, "gradient", "field");
  detail::require_positive_constants(c.re, c.n0, "gradient");
  grad.resize(x.size());
  const Scalar inv_n0 = Scalar(1) / c.n0;
  MPSFSI_OMP(parallel for schedule(static))
  for (std::int64_t ii = 0; ii < static_cast<std::int64_t>(x.size()); ++ii) {
    const auto i = static_cast<std::size_t>(ii);
    Scalar ref = phi[i];
    if (reference == GradientReference::neighbour_minimum) {
      for (Offset k = list.begin(i); k < list.end(i); ++k) {
        const Vec<Dim, Scalar> r = x[static_cast<std::size_t>(list.indices[k])] - x[i];
        if (Weight::value(detail::pair_distance(list, k, r), c.re) > Scalar(0))
          ref = std::min(ref, phi[static_cast<std::size_t>(list.indices[k])]);
      }
    }
    Vec<Dim, Scalar> sum = Vec<Dim, Scalar>::Zero();
    for (Offset k = list.begin(i); k < list.end(i); ++k) {
      const auto j = static_cast<std::size_t>(list.indices[k]);
      const Vec<Dim, Scalar> r = x[j] - x[i];
      const Scalar d = detail::pair_distance(list, k, r);
      const Scalar w = Weight::value(d, c.re);
      // Coincident particles (d = 0) have no direction: skip them rather than produce NaN.
      if (w == Scalar(0) || !(d > Scalar(0))) continue;
      sum += ((phi[j] - ref) * w / (d * d)) * r;
    }
    // C_i is constant over the sum, so it is applied once.
    grad[i] = inv_n0 * correction.apply(i, sum);
  }
}

}  // namespace MPSFSI_ABI
}  // namespace mpsfsi
