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

// MPS Laplacian of Koshizuka & Oka 1996:
//   <lap phi>_i = (2d / (lambda n0)) sum_j (phi_j - phi_i) w_ij,
// for a scalar field (T = Scalar) or a vector field (T = Vec<Dim>, component-wise, e.g. the
// viscous term nu lap u of eq 9). lambda and n0 come from the ideal lattice of the same re.
template <class Weight, int Dim, class Scalar, class T>
void laplacian(const VecArray<Dim, Scalar>& x, const BasicNeighborList<Scalar>& list,
               const std::vector<T>& phi, const MpsConstants<Scalar>& c, std::vector<T>& lap) {
  check_weight<Weight>();
  detail::require_list_rows(list, x.size(), "laplacian");
  detail::require_same_size(x, phi, "laplacian", "field");
  detail::require_positive_constants(c.re, c.n0, "laplacian");
  if (!(c.lambda > 0)) detail::throw_invalid("laplacian", "lambda must be positive");
  lap.resize(x.size());
  const Scalar coeff = Scalar(2 * Dim) / (c.lambda * c.n0);
  MPSFSI_OMP(parallel for schedule(static))
  for (std::int64_t ii = 0; ii < static_cast<std::int64_t>(x.size()); ++ii) {
    const auto i = static_cast<std::size_t>(ii);
    T sum = phi[i] - phi[i];  // a zero of the field's type, scalar or vector
    for (Offset k = list.begin(i); k < list.end(i); ++k) {
      const auto j = static_cast<std::size_t>(list.indices[k]);
      const Vec<Dim, Scalar> r = x[j] - x[i];
      const Scalar w = Weight::value(detail::pair_distance(list, k, r), c.re);
      sum += w * (phi[j] - phi[i]);
    }
    lap[i] = coeff * sum;
  }
}

}  // namespace MPSFSI_ABI
}  // namespace mpsfsi
