// SPDX-License-Identifier: BSD-3-Clause
#pragma once

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

// MPS divergence of a vector field with a correction policy:
//   <div u>_i = (1/n0) sum_j (u_j - u_i) . (C_i r_ij) / |r_ij|^2 w_ij,
// the standard (d/n0) sum_j (u_j - u_i) . r_ij / |r_ij|^2 w_ij for NoGradientCorrection, and the
// trace of the corrected velocity gradient for KhayyerGotohCorrection (exact for linear fields).
template <class Weight, int Dim, class Scalar, class Correction>
void divergence(const VecArray<Dim, Scalar>& x, const BasicNeighborList<Scalar>& list,
                const VecArray<Dim, Scalar>& u, const MpsConstants<Scalar>& c, const Correction& correction,
                std::vector<Scalar>& div) {
  check_weight<Weight>();
  detail::require_list_rows(list, x.size(), "divergence");
  detail::require_same_size(x, u, "divergence", "field");
  detail::require_positive_constants(c.re, c.n0, "divergence");
  div.resize(x.size());
  const Scalar inv_n0 = Scalar(1) / c.n0;
  MPSFSI_OMP(parallel for schedule(static))
  for (std::int64_t ii = 0; ii < static_cast<std::int64_t>(x.size()); ++ii) {
    const auto i = static_cast<std::size_t>(ii);
    // G = sum_j (u_j - u_i) r_ij^T w/|r|^2 is contracted with C_i once at the end:
    // sum_j du . (C_i r) w/|r|^2 = sum_ab G_ab (C_i)_ab, C_i being symmetric.
    Mat<Dim, Scalar> g = Mat<Dim, Scalar>::Zero();
    for (Offset k = list.begin(i); k < list.end(i); ++k) {
      const auto j = static_cast<std::size_t>(list.indices[k]);
      const Vec<Dim, Scalar> r = x[j] - x[i];
      const Scalar d = detail::pair_distance(list, k, r);
      const Scalar w = Weight::value(d, c.re);
      if (w == Scalar(0) || !(d > Scalar(0))) continue;  // coincident particles: no direction
      g.noalias() += (w / (d * d)) * ((u[j] - u[i]) * r.transpose());
    }
    Scalar s = 0;
    for (int a = 0; a < Dim; ++a) s += g.row(a).dot(correction.apply(i, Vec<Dim, Scalar>::Unit(a)));
    div[i] = inv_n0 * s;
  }
}

}  // namespace MPSFSI_ABI
}  // namespace mpsfsi
