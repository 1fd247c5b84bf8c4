// SPDX-License-Identifier: BSD-3-Clause
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <vector>

#include "mpsfsi/core/abi.hpp"
#include "mpsfsi/core/neighbor_list.hpp"
#include "mpsfsi/core/parallel.hpp"
#include "mpsfsi/core/types.hpp"

namespace mpsfsi {
inline namespace MPSFSI_ABI {
namespace detail {

// Per-thread buffers reused from one build to the next, so a steady-state rebuild allocates
// nothing once the buffers have grown to size. `length` is the part of each buffer in use; the
// vectors' sizes only grow.
template <class Scalar>
struct CsrScratch {
  std::vector<std::vector<Index>> indices;
  std::vector<std::vector<Scalar>> squared;
  std::vector<std::size_t> length;
};

// Where a query writes its candidates. Writes are unconditional and the length advances only
// for accepted ones, which keeps the distance test free of branches (a candidate is accepted
// about one time in three in 2D and one in eight in 3D, too often for a branch predictor).
template <class Scalar>
class CsrSink {
 public:
  CsrSink(std::vector<Index>& idx, std::vector<Scalar>& sq, bool keep_distances)
      : idx_(idx), sq_(sq), keep_(keep_distances) {}

  // Room for `extra` more candidates; call before put()-ing them.
  void reserve(std::size_t extra) {
    const std::size_t need = len_ + extra;
    if (idx_.size() < need) idx_.resize(std::max(need, 2 * idx_.size()));
    if (keep_ && sq_.size() < need) sq_.resize(std::max(need, 2 * sq_.size()));
  }
  void put(Index j, Scalar squared, bool accept) {
    idx_[len_] = j;
    if (keep_) sq_[len_] = squared;
    len_ += accept ? 1 : 0;
  }
  std::size_t length() const { return len_; }
  // The free slots, for writing several candidates at once (detail::append_within), and
  // advancing past the `accepted` of them written to the front. squared_slots() is null when
  // the distances are not kept.
  Index* index_slots() { return idx_.data() + len_; }
  Scalar* squared_slots() { return keep_ ? sq_.data() + len_ : nullptr; }
  void advance(std::size_t accepted) { len_ += accepted; }

 private:
  std::vector<Index>& idx_;
  std::vector<Scalar>& sq_;
  bool keep_;
  std::size_t len_ = 0;
};

// First query of block b when n queries are split into nb contiguous blocks.
inline std::size_t block_begin(std::size_t n, int b, int nb) {
  return n * static_cast<std::size_t>(b) / static_cast<std::size_t>(nb);
}

// Fills `out` in one pass over the queries: thread t takes the t-th contiguous block of queries
// and writes their neighbours to its own buffer and their counts to offsets; the blocks are then
// placed by a prefix sum and copied in parallel. `visit(i, sink)` must reserve room in the sink
// and put() every candidate j of query i with its squared distance and whether it is accepted.
// The result does not depend on the thread count.
template <class Scalar, class Visit>
void build_csr(std::size_t num_queries, const QueryOptions& options, CsrScratch<Scalar>& scratch,
               BasicNeighborList<Scalar>& out, Visit&& visit) {
  const int threads = parallel::max_threads();
  if (scratch.indices.size() < static_cast<std::size_t>(threads)) {
    scratch.indices.resize(static_cast<std::size_t>(threads));
    scratch.squared.resize(static_cast<std::size_t>(threads));
  }
  scratch.length.assign(static_cast<std::size_t>(threads) + 1, 0);
  out.offsets.resize(num_queries + 1);
  out.offsets[0] = 0;
  Offset* offsets = out.offsets.data();
  const bool keep = options.store_distances;

  // OpenMP may hand out fewer threads than asked for, so the team size is read inside.
  int team = 1;
  MPSFSI_OMP(parallel num_threads(threads)) {
    const int t = parallel::thread_id();
    const int nt = parallel::team_size();
    MPSFSI_OMP(single) team = nt;
    CsrSink<Scalar> sink(scratch.indices[static_cast<std::size_t>(t)],
                         scratch.squared[static_cast<std::size_t>(t)], keep);
    const std::size_t lo = block_begin(num_queries, t, nt);
    const std::size_t hi = block_begin(num_queries, t + 1, nt);
    for (std::size_t i = lo; i < hi; ++i) {
      const std::size_t before = sink.length();
      visit(i, sink);
      offsets[i + 1] = static_cast<Offset>(sink.length() - before);
    }
    scratch.length[static_cast<std::size_t>(t) + 1] = sink.length();
    MPSFSI_OMP(barrier)
    // Block t starts after all earlier blocks; a local prefix sum turns counts into offsets.
    Offset start = 0;
    for (int b = 0; b < t; ++b) start += static_cast<Offset>(scratch.length[static_cast<std::size_t>(b) + 1]);
    for (std::size_t i = lo; i < hi; ++i) offsets[i + 1] += (i == lo ? start : offsets[i]);
  }

  Offset total = 0;
  for (int t = 0; t < team; ++t) total += static_cast<Offset>(scratch.length[static_cast<std::size_t>(t) + 1]);
  out.indices.resize(static_cast<std::size_t>(total));
  out.distances.resize(keep ? out.indices.size() : 0);

  MPSFSI_OMP(parallel for schedule(static, 1) num_threads(team))
  for (int t = 0; t < team; ++t) {
    const std::size_t len = scratch.length[static_cast<std::size_t>(t) + 1];
    if (len == 0) continue;
    const Offset start = offsets[block_begin(num_queries, t, team)];
    const auto& idx = scratch.indices[static_cast<std::size_t>(t)];
    std::copy(idx.begin(), idx.begin() + static_cast<std::ptrdiff_t>(len), out.indices.begin() + start);
    if (keep) {
      const auto& sq = scratch.squared[static_cast<std::size_t>(t)];
      for (std::size_t k = 0; k < len; ++k) out.distances[static_cast<std::size_t>(start) + k] = std::sqrt(sq[k]);
    }
  }
}

}  // namespace detail
}  // namespace MPSFSI_ABI
}  // namespace mpsfsi
