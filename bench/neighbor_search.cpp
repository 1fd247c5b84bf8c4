// SPDX-License-Identifier: BSD-3-Clause
// Full neighbour-list rebuild (bin + query into CSR) on a jittered lattice with re = 2.1 l0:
// cell list against kd-tree, 2D and 3D, N = 1e3 .. 1e6, 1 and 2 threads; and the fluid step's
// rebuild (fluid_rebuild: re = 3.1 l0, distances stored), cell list, N = 1e4 and 1e5.
// Arguments: /N/threads. Counter "particles/s" is N per rebuild time (wall clock).
#include <benchmark/benchmark.h>

#include <cmath>

#include "mpsfsi/core/cell_list_search.hpp"
#include "mpsfsi/core/kd_tree_search.hpp"
#include "mpsfsi/core/parallel.hpp"
#include "mpsfsi/scenes/lattice.hpp"

using namespace mpsfsi;

namespace {

template <int Dim>
ParticleSet<Dim> jittered_lattice(std::int64_t n) {
  const double l0 = 1.0;
  const auto side = static_cast<double>(std::llround(std::pow(static_cast<double>(n), 1.0 / Dim))) - 1;
  auto set = scenes::lattice_box<Dim>(Vec<Dim>::Zero(), Vec<Dim>::Constant(side * l0), l0);
  scenes::jitter(set, 0.1 * l0);
  return set;
}

// A rebuild within `radius` (in l0), storing the distances or not.
template <class Search>
void rebuild_within(benchmark::State& state, double radius, bool distances) {
  constexpr int Dim = Search::dim;
  const auto set = jittered_lattice<Dim>(state.range(0));
  const int saved = parallel::max_threads();
  parallel::set_num_threads(static_cast<int>(state.range(1)));
  Search search(radius);
  NeighborList list;
  QueryOptions options;
  options.store_distances = distances;
  // One untimed rebuild: a simulation rebuilds every step into buffers that already have their
  // size, so the steady state, not the first allocation, is what is measured.
  search.build(set.positions());
  search.self_query(set.positions(), list, options);
  for (auto _ : state) {
    search.build(set.positions());
    search.self_query(set.positions(), list, options);
    benchmark::DoNotOptimize(list.indices.data());
    benchmark::ClobberMemory();
  }
  parallel::set_num_threads(saved);
  state.counters["particles"] = static_cast<double>(set.size());
  state.counters["pairs/particle"] = static_cast<double>(list.num_pairs()) / static_cast<double>(set.size());
  state.counters["particles/s"] =
      benchmark::Counter(static_cast<double>(set.size()), benchmark::Counter::kIsIterationInvariantRate);
}

// Within 2.1 l0 (the number density's and the gradient's radius), indices only.
template <class Search>
void rebuild(benchmark::State& state) {
  rebuild_within<Search>(state, 2.1, false);
}

// The fluid step's search: within 3.1 l0 (the Laplacian's radius), with the distances, from
// which the step cuts its lists at 2.1 l0.
template <class Search>
void fluid_rebuild(benchmark::State& state) {
  rebuild_within<Search>(state, 3.1, true);
}

void sizes(benchmark::internal::Benchmark* b) {
  for (std::int64_t n : {1000, 10000, 100000, 1000000})
    for (std::int64_t threads : {1, 2}) b->Args({n, threads});
  b->Unit(benchmark::kMillisecond)->UseRealTime();
}

void fluid_sizes(benchmark::internal::Benchmark* b) {
  for (std::int64_t n : {10000, 100000})
    for (std::int64_t threads : {1, 2}) b->Args({n, threads});
  b->Unit(benchmark::kMillisecond)->UseRealTime();
}

}  // namespace

BENCHMARK_TEMPLATE(rebuild, CellListSearch<2>)->Apply(sizes);
BENCHMARK_TEMPLATE(fluid_rebuild, CellListSearch<2>)->Apply(fluid_sizes);
BENCHMARK_TEMPLATE(fluid_rebuild, CellListSearch<3>)->Apply(fluid_sizes);
BENCHMARK_TEMPLATE(rebuild, CellListSearch<3>)->Apply(sizes);
BENCHMARK_TEMPLATE(rebuild, KdTreeSearch<2>)->Apply(sizes);
BENCHMARK_TEMPLATE(rebuild, KdTreeSearch<3>)->Apply(sizes);

BENCHMARK_MAIN();
