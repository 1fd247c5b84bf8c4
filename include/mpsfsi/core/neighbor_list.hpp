// SPDX-License-Identifier: BSD-3-Clause
#pragma once

#include <cstddef>
#include <vector>

#include "mpsfsi/core/abi.hpp"
#include "mpsfsi/core/types.hpp"

namespace mpsfsi {
inline namespace MPSFSI_ABI {

// Fixed-radius neighbour lists in compressed sparse row form: the neighbours of query i are
// indices[offsets[i] .. offsets[i+1]), in the order the search found them (deterministic for a
// given input, whatever the thread count). Distances |r_j - r_i| sit beside the indices when the
// search was asked to store them; they are those of the positions searched, and operators use
// them, so rebuild the list after particles move. Built once per step and shared by every operator of the step.
template <class Scalar = double>
struct BasicNeighborList {
  std::vector<Offset> offsets{0};
  std::vector<Index> indices;
  std::vector<Scalar> distances;  // empty unless requested

  std::size_t num_queries() const { return offsets.size() - 1; }
  std::size_t num_pairs() const { return indices.size(); }
  bool has_distances() const { return !indices.empty() && distances.size() == indices.size(); }

  Offset begin(std::size_t i) const { return offsets[i]; }
  Offset end(std::size_t i) const { return offsets[i + 1]; }
  Index count(std::size_t i) const { return static_cast<Index>(offsets[i + 1] - offsets[i]); }

  void clear() {
    offsets.assign(1, 0);
    indices.clear();
    distances.clear();
  }
};

using NeighborList = BasicNeighborList<double>;

// What a query stores besides the indices.
struct QueryOptions {
  bool store_distances = false;
};

}  // namespace MPSFSI_ABI
}  // namespace mpsfsi
