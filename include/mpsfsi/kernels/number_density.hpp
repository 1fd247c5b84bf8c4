// SPDX-License-Identifier: BSD-3-Clause
#pragma once

#include <cstdint>
#include <vector>

#include "mpsfsi/core/abi.hpp"
#include "mpsfsi/core/neighbor_list.hpp"
#include "mpsfsi/core/parallel.hpp"
#include "mpsfsi/core/types.hpp"
#include "mpsfsi/kernels/detail/pair.hpp"
#include "mpsfsi/kernels/weight.hpp"

namespace mpsfsi {
inline namespace MPSFSI_ABI {

// Particle number density, eq 12: n_i = sum_{j != i} w(|r_j - r_i|), over the neighbour list of
// the query points `x_query` into the source points `x_source` (the same array for a set looking
// at itself; another set for fluid counting wall or solid particles). The list's radius may
// exceed re: w vanishes beyond re. With `accumulate`, adds to n instead of overwriting it.
template <class Weight, int Dim, class Scalar>
void number_density(const VecArray<Dim, Scalar>& x_query, const VecArray<Dim, Scalar>& x_source,
                    const BasicNeighborList<Scalar>& list, Scalar re, std::vector<Scalar>& n,
                    bool accumulate = false) {
  check_weight<Weight>();
  detail::require_list_rows(list, x_query.size(), "number_density");
  if (accumulate) {
    detail::require_same_size(x_query, n, "number_density", "accumulated number density");
  } else {
    n.resize(x_query.size());
  }
  MPSFSI_OMP(parallel for schedule(static))
  for (std::int64_t ii = 0; ii < static_cast<std::int64_t>(x_query.size()); ++ii) {
    const auto i = static_cast<std::size_t>(ii);
    Scalar sum = 0;
    for (Offset k = list.begin(i); k < list.end(i); ++k) {
      const Vec<Dim, Scalar> r_ij = x_source[static_cast<std::size_t>(list.indices[k])] - x_query[i];
      sum += Weight::value(detail::pair_distance(list, k, r_ij), re);
    }
    n[i] = accumulate ? n[i] + sum : sum;
  }
}

// Number density of a set looking at itself.
template <class Weight, int Dim, class Scalar>
void number_density(const VecArray<Dim, Scalar>& x, const BasicNeighborList<Scalar>& list, Scalar re,
                    std::vector<Scalar>& n) {
  number_density<Weight>(x, x, list, re, n, false);
}

}  // namespace MPSFSI_ABI
}  // namespace mpsfsi
