// SPDX-License-Identifier: BSD-3-Clause
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <vector>

#include "mpsfsi/core/neighbor_list.hpp"
#include "mpsfsi/core/parallel.hpp"
#include "mpsfsi/core/types.hpp"

namespace mpsfsi::detail {

// Per-thread buffers reused from one build to the next, so a steady-state rebuild allocates
// nothing once the buffers have grown to size.
template <class Scalar>
struct CsrScratch {
  std::vector<std::vector<Index>> indices;
  std::vector<std::vector<Scalar>> squared;
};

// First query of block b when n queries are split into nb contiguous blocks.
inline std::size_t block_begin(std::size_t n, int b, int nb) {
  return n * static_cast<std::size_t>(b) / static_cast<std::size_t>(nb);
}

// Fills `out` in one pass over the queries: each thread takes a contiguous block of queries,
// appends their neighbours to its own buffer and writes the counts; a prefix sum then places
// the blocks. `visit(i, push)` must call push(j, squared_distance) for every neighbour j of i.
template <class Scalar, class Visit>
void build_csr(std::size_t num_queries, const QueryOptions& options, CsrScratch<Scalar>& scratch,
               BasicNeighborList<Scalar>& out, Visit&& visit) {
  const int threads = parallel::max_threads();
  if (scratch.indices.size() < static_cast<std::size_t>(threads)) {
    scratch.indices.resize(static_cast<std::size_t>(threads));
    scratch.squared.resize(static_cast<std::size_t>(threads));
  }
  out.offsets.resize(num_queries + 1);
  out.offsets[0] = 0;
  std::vector<Offset>& offsets = out.offsets;
  const bool keep = options.store_distances;

  // Block t of the queries belongs to thread t; the team size is read inside the region because
  // OpenMP may hand out fewer threads than asked for.
  int team = 1;
  MPSFSI_OMP(parallel num_threads(threads)) {
    const int t = parallel::thread_id();
    const int nt = parallel::team_size();
    MPSFSI_OMP(single) team = nt;
    auto& idx = scratch.indices[static_cast<std::size_t>(t)];
    auto& sq = scratch.squared[static_cast<std::size_t>(t)];
    idx.clear();
    sq.clear();
    const std::size_t lo = block_begin(num_queries, t, nt);
    const std::size_t hi = block_begin(num_queries, t + 1, nt);
    for (std::size_t i = lo; i < hi; ++i) {
      const std::size_t before = idx.size();
      visit(i, [&](Index j, Scalar d2) {
        idx.push_back(j);
        if (keep) sq.push_back(d2);
      });
      offsets[i + 1] = static_cast<Offset>(idx.size() - before);
    }
  }

  for (std::size_t i = 0; i < num_queries; ++i) offsets[i + 1] += offsets[i];
  out.indices.resize(static_cast<std::size_t>(offsets[num_queries]));
  out.distances.resize(keep ? out.indices.size() : 0);

  MPSFSI_OMP(parallel for schedule(static, 1) num_threads(team))
  for (int t = 0; t < team; ++t) {
    const auto& idx = scratch.indices[static_cast<std::size_t>(t)];
    if (idx.empty()) continue;
    // The first query of block t is where its buffer starts in the global arrays.
    const Offset start = offsets[block_begin(num_queries, t, team)];
    std::copy(idx.begin(), idx.end(), out.indices.begin() + start);
    if (keep) {
      const auto& sq = scratch.squared[static_cast<std::size_t>(t)];
      for (std::size_t k = 0; k < sq.size(); ++k)
        out.distances[static_cast<std::size_t>(start) + k] = std::sqrt(sq[k]);
    }
  }
}

}  // namespace mpsfsi::detail
