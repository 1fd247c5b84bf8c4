// SPDX-License-Identifier: BSD-3-Clause
#pragma once

#include <cmath>
#include <cstddef>
#include <string>

#include "mpsfsi/core/abi.hpp"
#include "mpsfsi/core/detail/format.hpp"
#include "mpsfsi/core/error.hpp"
#include "mpsfsi/core/neighbor_list.hpp"
#include "mpsfsi/core/types.hpp"

namespace mpsfsi {
inline namespace MPSFSI_ABI {
namespace detail {

// |r_ij| for entry k of a neighbour list: the stored distance when the search kept it.
template <int Dim, class Scalar>
inline Scalar pair_distance(const BasicNeighborList<Scalar>& list, Offset k, const Vec<Dim, Scalar>& r_ij) {
  return list.has_distances() ? list.distances[static_cast<std::size_t>(k)] : r_ij.norm();
}

template <class Scalar>
inline void require_list_rows(const BasicNeighborList<Scalar>& list, std::size_t n, const char* where) {
  if (list.num_queries() != n)
    throw_invalid(where, "neighbour list has " + std::to_string(list.num_queries()) +
                             " rows for " + std::to_string(n) + " particles; rebuild it");
}

template <class A, class B>
inline void require_same_size(const A& a, const B& b, const char* where, const char* what) {
  if (a.size() != b.size())
    throw_invalid(where, std::string(what) + " has " + std::to_string(b.size()) + " entries for " +
                             std::to_string(a.size()) + " particles");
}

template <class Scalar>
inline void require_positive_constants(Scalar re, Scalar n0, const char* where) {
  if (!(re > 0) || !(n0 > 0))
    throw_invalid(where, "re and n0 must be positive (re = " + detail::format_number(re) +
                             ", n0 = " + detail::format_number(n0) + ")");
}

}  // namespace detail
}  // namespace MPSFSI_ABI
}  // namespace mpsfsi
