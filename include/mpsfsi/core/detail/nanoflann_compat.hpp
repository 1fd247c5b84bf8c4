// SPDX-License-Identifier: BSD-3-Clause
#pragma once

// Every use of nanoflann goes through this header. Debian 12 ships nanoflann 1.4.x, whose search
// options are `SearchParams` and whose results are std::pair; 1.5 renamed them to
// `SearchParameters` and `ResultItem`. mpsfsi avoids the result types altogether by passing its
// own result-set callback, so only the options type differs.

#include <cstddef>
#include <nanoflann.hpp>

#include "mpsfsi/core/abi.hpp"

#if !defined(NANOFLANN_VERSION)
#error "mpsfsi: nanoflann.hpp did not define NANOFLANN_VERSION"
#endif

namespace mpsfsi {
inline namespace MPSFSI_ABI {
namespace detail {
namespace nanoflann_compat {

#if NANOFLANN_VERSION >= 0x150
using SearchParameters = nanoflann::SearchParameters;
inline SearchParameters unsorted_search() {
  SearchParameters p;
  p.sorted = false;
  return p;
}
#else
using SearchParameters = nanoflann::SearchParams;
inline SearchParameters unsorted_search() { return SearchParameters(32, 0.0f, false); }
#endif

// Every version builds the index in the tree's constructor (the flag to defer it only exists
// from 1.4.3 on, and Debian's 1.4.3 calls itself 1.4.2), so a rebuild constructs a new tree.
inline nanoflann::KDTreeSingleIndexAdaptorParams tree_parameters(std::size_t leaf_max_size) {
  return nanoflann::KDTreeSingleIndexAdaptorParams(leaf_max_size);
}

// A radius result set that forwards each point to a callback instead of storing it. nanoflann
// passes points with squared distance strictly below worstDist(); the callback applies the
// library's own inclusive test, so worstDist() is set a hair above the radius.
template <class DistanceType_, class IndexType_, class Callback>
class CallbackResultSet {
 public:
  using DistanceType = DistanceType_;  // read by nanoflann 1.7+
  using IndexType = IndexType_;
  CallbackResultSet(DistanceType worst, Callback& callback) : worst_(worst), callback_(callback) {}
  void init() {}
  void clear() {}
  std::size_t size() const { return 0; }
  bool empty() const { return true; }
  bool full() const { return true; }
  bool addPoint(DistanceType /*squared*/, IndexType index) {
    callback_(index);
    return true;
  }
  DistanceType worstDist() const { return worst_; }
  void sort() {}

 private:
  DistanceType worst_;
  Callback& callback_;
};

}  // namespace nanoflann_compat
}  // namespace detail
}  // namespace MPSFSI_ABI
}  // namespace mpsfsi
