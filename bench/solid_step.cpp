// SPDX-License-Identifier: BSD-3-Clause
// ElasticSolver throughput: one whole step of a block of material with every particle
// free and the first-mode velocity field of a clamped plate (so every bond is stretched), in
// bond evaluations per second: directed bonds (each pair counted from both ends) times steps.
// Arguments: /particles along the long side/threads. Target: >= 2e8 bond evaluations per
// second per core in 2D, double precision.
#include <benchmark/benchmark.h>

#include <cmath>

#include "mpsfsi/core/parallel.hpp"
#include "bench_plate.hpp"
#include "mpsfsi/solid/elastic_solver.hpp"

using namespace mpsfsi;

namespace {

template <int Dim, class Policies>
void solid_step(benchmark::State& state) {
  const int saved = parallel::max_threads();
  parallel::set_num_threads(static_cast<int>(state.range(1)));
  bench::BenchPlate<Dim> plate(state.range(0));
  ElasticSolver<Dim, Policies> solver(plate.particles, plate.params);
  for (const auto i : plate.clamped) solver.clamp(i);
  for (int k = 0; k < 10; ++k) solver.step();
  for (auto _ : state) solver.step();
  parallel::set_num_threads(saved);
  const auto bonds = static_cast<double>(solver.bond_evaluations_per_step());
  state.counters["particles"] = static_cast<double>(solver.particles().size());
  state.counters["bonds/particle"] = bonds / static_cast<double>(solver.particles().size());
  state.counters["bond_evals/s"] = benchmark::Counter(bonds, benchmark::Counter::kIsIterationInvariantRate);
  state.counters["bond_evals/s/thread"] =
      benchmark::Counter(bonds / static_cast<double>(state.range(1)), benchmark::Counter::kIsIterationInvariantRate);
}

}  // namespace

// 2D: 10 x 100 .. 40 x 400 particles; 3D: 10 x 10 x 100 (arguments /length/threads).
BENCHMARK_TEMPLATE(solid_step, 2, SolidDefaults<2>)
    ->Args({100, 1})
    ->Args({400, 1})
    ->Args({400, 2})
    ->Unit(benchmark::kMicrosecond)
    ->UseRealTime();
BENCHMARK_TEMPLATE(solid_step, 2, PaperSolidPolicies<2>)->Args({400, 1})->Args({400, 2})->Unit(benchmark::kMicrosecond)->UseRealTime();
BENCHMARK_TEMPLATE(solid_step, 3, SolidDefaults<3>)->Args({100, 1})->Args({100, 2})->Unit(benchmark::kMicrosecond)->UseRealTime();
BENCHMARK_MAIN();
