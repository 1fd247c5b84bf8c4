// SPDX-License-Identifier: BSD-3-Clause
// Every neighbour list is compared with a brute-force O(N^2) one: random and lattice sets, pairs
// at exactly the radius, coincident particles, particles far outside the box, empty sets, two
// sets, and 1 and 2 threads.
#include <doctest/doctest.h>

#include <cmath>
#include <random>

#include "mpsfsi/core/cell_list_search.hpp"
#include "mpsfsi/core/kd_tree_search.hpp"
#include "mpsfsi/core/neighbor_search.hpp"
#include "mpsfsi/core/parallel.hpp"
#include "mpsfsi/scenes/lattice.hpp"
#include "support/brute_force.hpp"

using namespace mpsfsi;

namespace {

template <int D, template <int, class> class S>
struct Case {
  static constexpr int dim = D;
  using search = S<D, double>;
};

template <int Dim>
VecArray<Dim> random_points(std::size_t n, double box, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(0.0, box);
  VecArray<Dim> p(n);
  for (auto& x : p)
    for (int k = 0; k < Dim; ++k) x[k] = u(rng);
  return p;
}

template <class Search, int Dim>
void check_self(const VecArray<Dim>& pts, double radius, bool distances = false) {
  Search search(radius);
  search.build(pts);
  NeighborList list;
  QueryOptions opt;
  opt.store_distances = distances;
  search.self_query(pts, list, opt);
  REQUIRE(list.num_queries() == pts.size());
  const auto expected = test::brute_force_neighbors<Dim, double>(pts, pts, radius, true);
  const auto got = test::sorted_rows(list);
  for (std::size_t i = 0; i < pts.size(); ++i) {
    INFO("particle " << i);
    CHECK(got[i] == expected[i]);
  }
  if (distances) {
    REQUIRE(list.has_distances());
    for (std::size_t i = 0; i < pts.size(); ++i)
      for (Offset k = list.begin(i); k < list.end(i); ++k)
        CHECK(list.distances[k] == doctest::Approx((pts[list.indices[k]] - pts[i]).norm()).epsilon(1e-14));
  }
}

}  // namespace

TEST_SUITE("core") {

TEST_CASE_TEMPLATE("core.neighbor_search: matches brute force", C, Case<2, CellListSearch>,
                   Case<3, CellListSearch>, Case<2, KdTreeSearch>, Case<3, KdTreeSearch>) {
  constexpr int Dim = C::dim;
  using S = typename C::search;
  static_assert(check_neighbor_search<S>());

  SUBCASE("random set") { check_self<S, Dim>(random_points<Dim>(Dim == 2 ? 800 : 1500, 10.0, 7), 1.3, true); }

  SUBCASE("lattice with pairs at exactly the radius") {
    // Integer lattice, radius 2: pairs at distance exactly 2 (and sqrt(2), sqrt(3)) are exact in
    // binary, so the inclusive test must keep the distance-2 pairs.
    auto set = scenes::lattice_box<Dim>(Vec<Dim>::Zero(), Vec<Dim>::Constant(Dim == 2 ? 12.0 : 6.0), 1.0);
    check_self<S, Dim>(set.positions(), 2.0);
    S search(2.0);
    search.build(set.positions());
    NeighborList list;
    search.self_query(set.positions(), list);
    // An interior particle of the integer lattice has 12 (2D) or 32 (3D) neighbours within 2.
    const std::size_t centre = Dim == 2 ? 6 * 13 + 6 : (3 * 7 + 3) * 7 + 3;
    CHECK(list.count(centre) == (Dim == 2 ? 12 : 32));
  }

  SUBCASE("pairs tied at the radius in the reference arithmetic") {
    // The radius is set so that r * r equals the squared distance of points 0 and 1 as
    // detail::squared_distance forms it: the search must keep that pair, whichever way (one
    // candidate at a time or several side by side) it forms the distance. About 25 points a
    // cell, so the runs are long enough for the side-by-side path.
    int tied = 0;
    for (unsigned trial = 0; trial < 60; ++trial) {
      const auto pts = random_points<Dim>(Dim == 2 ? 250 : 700, 3.0, 100 + trial);
      const double d2 = detail::squared_distance<Dim, double>(pts[0], pts[1]);
      double r = std::sqrt(d2);
      for (int nudge = 0; nudge < 4 && r * r != d2; ++nudge) r = std::nextafter(r, r * r < d2 ? 2 * r : 0.0);
      if (r * r != d2 || !(r > 0.5)) continue;
      ++tied;
      check_self<S, Dim>(pts, r);
    }
    CHECK(tied >= 20);
  }

  SUBCASE("coincident particles are each other's neighbours") {
    auto pts = random_points<Dim>(200, 4.0, 3);
    pts.push_back(pts[10]);
    pts.push_back(pts[10]);
    check_self<S, Dim>(pts, 0.7);
  }

  SUBCASE("particles far outside the box") {
    auto pts = random_points<Dim>(300, 5.0, 11);
    pts.push_back(Vec<Dim>::Constant(1e7));
    pts.push_back(Vec<Dim>::Constant(1e7) + Vec<Dim>::Unit(0) * 0.5);
    pts.push_back(Vec<Dim>::Constant(-3e5));
    check_self<S, Dim>(pts, 0.8);
  }

  SUBCASE("empty and single-particle sets") {
    VecArray<Dim> none;
    S search(1.0);
    search.build(none);
    NeighborList list;
    search.self_query(none, list);
    CHECK(list.num_queries() == 0);
    CHECK(list.num_pairs() == 0);
    VecArray<Dim> q = random_points<Dim>(5, 1.0, 1);
    search.query(q, list);
    CHECK(list.num_queries() == 5);
    CHECK(list.num_pairs() == 0);
    VecArray<Dim> one(1, Vec<Dim>::Zero());
    search.build(one);
    search.self_query(one, list);
    CHECK(list.count(0) == 0);
  }

  SUBCASE("two sets: queries against another set") {
    const auto sources = random_points<Dim>(600, 6.0, 21);
    auto queries = random_points<Dim>(250, 8.0, 22);
    queries.push_back(sources[3]);                   // coincident with a source: kept
    queries.push_back(Vec<Dim>::Constant(-50.0));    // far outside: none
    S search(1.1);
    search.build(sources);
    NeighborList list;
    search.query(queries, list);
    const auto expected = test::brute_force_neighbors<Dim, double>(queries, sources, 1.1, false);
    CHECK(test::sorted_rows(list) == expected);
    CHECK(list.count(queries.size() - 1) == 0);
  }

  SUBCASE("one and two threads give identical lists") {
    const auto pts = random_points<Dim>(3000, 15.0, 5);
    S search(1.2);
    search.build(pts);
    NeighborList one, two;
    const int saved = parallel::max_threads();
    parallel::set_num_threads(1);
    search.self_query(pts, one);
    parallel::set_num_threads(2);
    search.self_query(pts, two);
    parallel::set_num_threads(saved);
    CHECK(one.offsets == two.offsets);
    CHECK(one.indices == two.indices);
  }

  SUBCASE("invalid input") {
    CHECK_THROWS_AS(S(0.0), InvalidInput);
    CHECK_THROWS_AS(S(-1.0), InvalidInput);
    CHECK_THROWS_AS(S(std::nan("")), InvalidInput);
    auto pts = random_points<Dim>(20, 1.0, 2);
    pts[7][0] = std::nan("");
    S search(0.5);
    CHECK_THROWS_WITH_AS(search.build(pts), doctest::Contains("point 7"), InvalidInput);
    pts[7][0] = 0.5;
    search.build(pts);
    NeighborList list;
    pts.pop_back();
    CHECK_THROWS_AS(search.self_query(pts, list), InvalidInput);
  }
}

TEST_CASE_TEMPLATE("core.neighbor_search: cell list and kd-tree agree", V, Vec<2>, Vec<3>) {
  constexpr int Dim = static_cast<int>(V::RowsAtCompileTime);
  auto set = scenes::lattice_box<Dim>(Vec<Dim>::Zero(), Vec<Dim>::Constant(Dim == 2 ? 30.0 : 9.0), 1.0);
  scenes::jitter(set, 0.2);
  CellListSearch<Dim> cells(2.1);
  KdTreeSearch<Dim> tree(2.1);
  cells.build(set.positions());
  tree.build(set.positions());
  NeighborList a, b;
  cells.self_query(set.positions(), a);
  tree.self_query(set.positions(), b);
  CHECK(test::sorted_rows(a) == test::sorted_rows(b));
}

TEST_CASE_TEMPLATE("core.neighbor_search: reordering by cell permutes every field", V, Vec<2>, Vec<3>) {
  constexpr int Dim = static_cast<int>(V::RowsAtCompileTime);
  ParticleSet<Dim> set;
  const auto pts = random_points<Dim>(500, 10.0, 9);
  for (const auto& p : pts) set.add(p);
  auto tag = set.template add_field<double>("tag");
  for (std::size_t i = 0; i < set.size(); ++i) {
    set.velocities()[i] = 2.0 * set.positions()[i];
    set.field(tag)[i] = static_cast<double>(i);
  }
  CellListSearch<Dim> search(1.0);
  const auto new_to_old = reorder_by_cell(set, search);
  for (std::size_t k = 0; k < set.size(); ++k) {
    const auto old = static_cast<std::size_t>(new_to_old[k]);
    CHECK(set.positions()[k] == pts[old]);
    CHECK(set.velocities()[k] == 2.0 * pts[old]);
    CHECK(set.field(tag)[k] == static_cast<double>(old));
    CHECK(set.ids()[k] == static_cast<Index>(old));
  }
  // After the reorder the set is in cell order: the cell order is now the identity.
  for (std::size_t k = 0; k < set.size(); ++k) CHECK(search.cell_order()[k] == static_cast<Index>(k));
  check_self<CellListSearch<Dim>, Dim>(set.positions(), 1.0);
}

}  // TEST_SUITE
