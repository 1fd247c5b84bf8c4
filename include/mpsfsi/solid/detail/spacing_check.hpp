// SPDX-License-Identifier: BSD-3-Clause
#pragma once

#include <string>
#include <vector>

#include "mpsfsi/core/abi.hpp"
#include "mpsfsi/core/cell_list_search.hpp"
#include "mpsfsi/core/detail/format.hpp"
#include "mpsfsi/core/detail/spacing.hpp"
#include "mpsfsi/core/error.hpp"
#include "mpsfsi/core/types.hpp"

namespace mpsfsi {
inline namespace MPSFSI_ABI {
namespace detail {

// ElasticSolver's check of its particles against l0: two particles closer than l0/2 overlap, no
// two within 1.5 l0 means a spacing wider than l0, and a median nearest-neighbour distance more
// than 10 % off l0 (check_median_spacing) is an error. Throws InvalidInput naming the problem.
template <int Dim>
void check_solid_spacing(const VecArray<Dim, double>& x, double l0) {
  const std::size_t n = x.size();
  if (n < 2) return;
  const double radius = 1.5 * l0;
  CellListSearch<Dim, double> search(radius);
  search.build(x);
  BasicNeighborList<double> close;
  search.self_query(x, close, QueryOptions{true});
  std::vector<double> nearest;
  nearest.reserve(n);
  for (std::size_t i = 0; i < n; ++i) {
    if (close.begin(i) == close.end(i)) continue;
    double d = radius;
    Index j = -1;
    for (Offset k = close.begin(i); k < close.end(i); ++k) {
      const double dk = close.distances[static_cast<std::size_t>(k)];
      if (dk < d) d = dk, j = close.indices[static_cast<std::size_t>(k)];
    }
    if (d < 0.5 * l0 * (1 - 1e-9))
      throw_invalid("ElasticSolver", "particles " + std::to_string(i) + " and " + std::to_string(j) +
                                         " overlap (closer than l0/2)");
    nearest.push_back(d);
  }
  if (nearest.empty())
    throw_invalid("ElasticSolver", "no two particles are within 1.5 l0 of each other (l0 = " + format_number(l0) +
                                       " m): the particles are spaced more widely than l0");
  check_median_spacing(nearest, l0, "ElasticSolver");
}

}  // namespace detail
}  // namespace MPSFSI_ABI
}  // namespace mpsfsi
