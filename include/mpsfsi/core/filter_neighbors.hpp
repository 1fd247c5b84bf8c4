// SPDX-License-Identifier: BSD-3-Clause
#pragma once

#include <cstdint>
#include <type_traits>
#include <vector>

#include "mpsfsi/core/abi.hpp"
#include "mpsfsi/core/neighbor_list.hpp"
#include "mpsfsi/core/parallel.hpp"
#include "mpsfsi/core/types.hpp"

namespace mpsfsi {
inline namespace MPSFSI_ABI {
namespace detail {

template <class Keep>
bool keep_pair(Keep& keep, std::size_t i, Index j, Offset k) {
  if constexpr (std::is_invocable_v<Keep&, std::size_t, Index, Offset>) return keep(i, j, k);
  else if constexpr (std::is_invocable_v<Keep&, std::size_t, Index>) return keep(i, j);
  else return keep(j);
}

}  // namespace detail

// Copies the entries (j, distance) of `in` for which keep(j) (or keep(i, j), if keep takes the
// row too, or keep(i, j, k), k the entry's position in `in`, e.g. to read in.distances[k]) holds
// into `out`, row by row, in their order, so operators that must not see some particles (e.g.
// the pressure gradient and the dummy wall particles) reuse the step's one search. Allocates
// only while `out` grows.
template <class Scalar, class Keep>
void filter_neighbors(const BasicNeighborList<Scalar>& in, Keep&& keep, BasicNeighborList<Scalar>& out) {
  const std::size_t n = in.num_queries();
  out.offsets.resize(n + 1);
  out.offsets[0] = 0;
  MPSFSI_OMP(parallel for schedule(static))
  for (std::int64_t ii = 0; ii < static_cast<std::int64_t>(n); ++ii) {
    const auto i = static_cast<std::size_t>(ii);
    Offset c = 0;
    for (Offset k = in.begin(i); k < in.end(i); ++k) c += detail::keep_pair(keep, i, in.indices[k], k) ? 1 : 0;
    out.offsets[i + 1] = c;
  }
  for (std::size_t i = 0; i < n; ++i) out.offsets[i + 1] += out.offsets[i];
  out.indices.resize(static_cast<std::size_t>(out.offsets[n]));
  const bool dist = in.has_distances();
  out.distances.resize(dist ? out.indices.size() : 0);
  // Each entry is written to the next free slot, which advances only if the entry is kept: no
  // branch on the test, which the fluid step's cut by distance passes about 3 times in 10 (3D)
  // to 4 (2D), too often for a branch predictor (docs/performance.md, short neighbour lists).
  // Once the row is full the rest are all dropped, so nothing is written past it.
  MPSFSI_OMP(parallel for schedule(static))
  for (std::int64_t ii = 0; ii < static_cast<std::int64_t>(n); ++ii) {
    const auto i = static_cast<std::size_t>(ii);
    Offset p = out.offsets[i];
    const Offset full = out.offsets[i + 1];
    for (Offset k = in.begin(i); k < in.end(i) && p < full; ++k) {
      const Index j = in.indices[k];
      const bool kept = detail::keep_pair(keep, i, j, k);
      out.indices[p] = j;
      if (dist) out.distances[p] = in.distances[k];
      p += kept ? 1 : 0;
    }
  }
}

}  // namespace MPSFSI_ABI
}  // namespace mpsfsi
