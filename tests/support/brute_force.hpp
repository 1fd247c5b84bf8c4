// SPDX-License-Identifier: BSD-3-Clause
#pragma once

#include <algorithm>
#include <vector>

#include "mpsfsi/core/neighbor_list.hpp"
#include "mpsfsi/core/types.hpp"

namespace mpsfsi::test {

// O(N^2) reference: for every query, the sorted indices of the sources within the radius.
template <int Dim, class Scalar>
std::vector<std::vector<Index>> brute_force_neighbors(const VecArray<Dim, Scalar>& queries,
                                                      const VecArray<Dim, Scalar>& sources, Scalar radius,
                                                      bool exclude_self) {
  std::vector<std::vector<Index>> rows(queries.size());
  const Scalar r2 = radius * radius;
  for (std::size_t i = 0; i < queries.size(); ++i)
    for (std::size_t j = 0; j < sources.size(); ++j) {
      if (exclude_self && i == j) continue;
      if (detail::squared_distance<Dim, Scalar>(queries[i], sources[j]) <= r2)
        rows[i].push_back(static_cast<Index>(j));
    }
  return rows;
}

// A CSR list as sorted rows, for comparison with the reference.
template <class Scalar>
std::vector<std::vector<Index>> sorted_rows(const BasicNeighborList<Scalar>& list) {
  std::vector<std::vector<Index>> rows(list.num_queries());
  for (std::size_t i = 0; i < rows.size(); ++i) {
    rows[i].assign(list.indices.begin() + list.begin(i), list.indices.begin() + list.end(i));
    std::sort(rows[i].begin(), rows[i].end());
  }
  return rows;
}

}  // namespace mpsfsi::test
