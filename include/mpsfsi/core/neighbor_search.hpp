// SPDX-License-Identifier: BSD-3-Clause
#pragma once

#include <type_traits>
#include <utility>

#include "mpsfsi/core/abi.hpp"
#include "mpsfsi/core/cell_list_search.hpp"
#include "mpsfsi/core/kd_tree_search.hpp"
#include "mpsfsi/core/neighbor_list.hpp"
#include "mpsfsi/core/particle_set.hpp"
#include "mpsfsi/core/types.hpp"

namespace mpsfsi {
inline namespace MPSFSI_ABI {

// A neighbour search is any type with the members of CellListSearch<Dim, Scalar>:
//   static constexpr int dim; using scalar_type;
//   explicit Search(scalar_type radius);
//   void build(const VecArray<dim, scalar_type>& points);
//   void query(const VecArray<dim, scalar_type>& queries, BasicNeighborList<scalar_type>&, const QueryOptions&) const;
//   void self_query(const VecArray<dim, scalar_type>& points, BasicNeighborList<scalar_type>&, const QueryOptions&) const;
// Solvers take it as a policy; check_neighbor_search<S>() names what a candidate lacks.
namespace detail {

template <class S, class = void>
struct has_search_build : std::false_type {};
template <class S>
struct has_search_build<S, std::void_t<decltype(std::declval<S&>().build(
                               std::declval<const VecArray<S::dim, typename S::scalar_type>&>()))>>
    : std::true_type {};

template <class S, class = void>
struct has_search_query : std::false_type {};
template <class S>
struct has_search_query<S, std::void_t<decltype(std::declval<const S&>().query(
                               std::declval<const VecArray<S::dim, typename S::scalar_type>&>(),
                               std::declval<BasicNeighborList<typename S::scalar_type>&>(),
                               std::declval<const QueryOptions&>()))>> : std::true_type {};

template <class S, class = void>
struct has_search_self_query : std::false_type {};
template <class S>
struct has_search_self_query<S, std::void_t<decltype(std::declval<const S&>().self_query(
                                    std::declval<const VecArray<S::dim, typename S::scalar_type>&>(),
                                    std::declval<BasicNeighborList<typename S::scalar_type>&>(),
                                    std::declval<const QueryOptions&>()))>> : std::true_type {};

}  // namespace detail

template <class S>
constexpr bool check_neighbor_search() {
  static_assert(detail::has_search_build<S>::value,
                "neighbour search policy lacks build(const VecArray<dim, scalar_type>&)");
  static_assert(detail::has_search_query<S>::value,
                "neighbour search policy lacks query(queries, BasicNeighborList&, const QueryOptions&) const");
  static_assert(detail::has_search_self_query<S>::value,
                "neighbour search policy lacks self_query(points, BasicNeighborList&, const QueryOptions&) const");
  return true;
}

// Sorts the particles of a set by grid cell (every field permuted together), so that particles
// that are neighbours in space are neighbours in memory. The search is rebuilt on the new order.
// Returns the permutation applied (new index k held old index result[k]).
template <int Dim, class Scalar>
std::vector<Index> reorder_by_cell(ParticleSet<Dim, Scalar>& particles, CellListSearch<Dim, Scalar>& search) {
  search.build(particles.positions());
  std::vector<Index> new_to_old = search.cell_order();
  particles.permute(new_to_old);
  search.build(particles.positions());
  return new_to_old;
}

}  // namespace MPSFSI_ABI
}  // namespace mpsfsi
