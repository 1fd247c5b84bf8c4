// SPDX-License-Identifier: BSD-3-Clause
// filter_neighbors against a plain copy of the kept entries: keep(j), keep(i, j) and
// keep(i, j, k), with and without distances, rows that keep all, none, or drop their last
// entries, and 1 and 2 threads.
#include <doctest/doctest.h>

#include <random>
#include <vector>

#include "mpsfsi/core/cell_list_search.hpp"
#include "mpsfsi/core/filter_neighbors.hpp"
#include "mpsfsi/core/parallel.hpp"

using namespace mpsfsi;

namespace {

NeighborList random_list(bool distances) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(0.0, 6.0);
  VecArray<2> points(400);
  for (auto& p : points) p = Vec<2>(u(rng), u(rng));
  CellListSearch<2> search(0.9);
  search.build(points);
  NeighborList list;
  QueryOptions options;
  options.store_distances = distances;
  search.self_query(points, list, options);
  return list;
}

// The kept entries of `in`, row by row, written out one by one.
template <class Keep>
NeighborList reference(const NeighborList& in, Keep keep) {
  NeighborList out;
  out.offsets.assign(1, 0);
  for (std::size_t i = 0; i < in.num_queries(); ++i) {
    for (Offset k = in.begin(i); k < in.end(i); ++k) {
      if (!keep(i, in.indices[k], k)) continue;
      out.indices.push_back(in.indices[k]);
      if (in.has_distances()) out.distances.push_back(in.distances[k]);
    }
    out.offsets.push_back(static_cast<Offset>(out.indices.size()));
  }
  return out;
}

void check_same(const NeighborList& got, const NeighborList& expected) {
  CHECK(got.offsets == expected.offsets);
  CHECK(got.indices == expected.indices);
  CHECK(got.distances == expected.distances);
}

}  // namespace

TEST_SUITE("core") {

TEST_CASE("core.filter_neighbors: keeps the entries the test keeps, in their order") {
  const int saved = parallel::max_threads();
  for (const bool distances : {false, true}) {
    const NeighborList all = random_list(distances);
    REQUIRE(all.num_pairs() > 1000);
    for (const int threads : {1, 2}) {
      parallel::set_num_threads(threads);
      INFO("distances " << distances << ", threads " << threads);
      NeighborList out;
      // keep(j): every third particle.
      filter_neighbors(all, [](Index j) { return j % 3 != 0; }, out);
      check_same(out, reference(all, [](std::size_t, Index j, Offset) { return j % 3 != 0; }));
      // keep(i, j): rows of even particles keep everything, odd rows nothing.
      filter_neighbors(all, [](std::size_t i, Index) { return i % 2 == 0; }, out);
      check_same(out, reference(all, [](std::size_t i, Index, Offset) { return i % 2 == 0; }));
      // keep(i, j, k): each row's first half only, so every row drops its last entries.
      auto first_half = [&](std::size_t i, Index, Offset k) { return 2 * (k - all.begin(i)) < all.count(i); };
      filter_neighbors(all, first_half, out);
      check_same(out, reference(all, first_half));
    }
  }
  parallel::set_num_threads(saved);
}

}  // TEST_SUITE
