// SPDX-License-Identifier: BSD-3-Clause
// One whole FluidSolver step of the 2D dam break (docs/performance.md): a 0.25 m x 0.5 m
// water column in a 1 m x 0.6 m tank, l0 = 5 mm, dt = 2e-4 s, PPE relative residual 1e-8.
// The solver is first run to t = 0.1 s (the column is collapsing); each benchmark iteration is
// one step from there on. Arguments: /threads/start time in ms. Counters: particle-steps per
// second, the share of the step spent in the PPE solve, CG iterations and the milliseconds of
// each phase a step.
#include <benchmark/benchmark.h>

#include "dam_break_scaled.hpp"
#include "mpsfsi/core/parallel.hpp"
#include "mpsfsi/fluid/fluid_solver.hpp"
#include "mpsfsi/scenes/dam_break.hpp"
#if defined(MPSFSI_BENCH_HYPRE)
#include "mpsfsi/fluid/hypre_amg.hpp"
#endif

using namespace mpsfsi;

namespace {

// Runs the timed steps of `solver` and sets the counters: particle-steps per second, the share
// of the step in the PPE solve, CG iterations and the milliseconds of each phase a step.
template <class Solver>
void time_steps(benchmark::State& state, Solver& solver) {
  FluidStepTimings sum;
  double iterations = 0;
  for (auto _ : state) {
    solver.step();
    const FluidStepTimings& t = solver.last_timings();
    sum.search += t.search;
    sum.predictor += t.predictor;
    sum.ppe_assembly += t.ppe_assembly;
    sum.ppe_solve += t.ppe_solve;
    sum.corrector += t.corrector;
    iterations += solver.last_solve().iterations;
  }
  const auto n = static_cast<double>(solver.particles().size());
  state.counters["particles"] = n;
  state.counters["particle-steps/s"] = benchmark::Counter(n, benchmark::Counter::kIsIterationInvariantRate);
  state.counters["ppe_solve_share"] = sum.ppe_solve / sum.total();
  // Milliseconds per step in each phase (FluidSolver::last_timings).
  const double per_step_ms = 1e3 / static_cast<double>(state.iterations());
  state.counters["search_ms"] = sum.search * per_step_ms;
  state.counters["predictor_ms"] = sum.predictor * per_step_ms;
  state.counters["assembly_ms"] = sum.ppe_assembly * per_step_ms;
  state.counters["solve_ms"] = sum.ppe_solve * per_step_ms;
  state.counters["corrector_ms"] = sum.corrector * per_step_ms;
  state.counters["cg_iterations"] = iterations / static_cast<double>(state.iterations());
}

template <class Policies>
void dam_break_step(benchmark::State& state) {
  const int saved = parallel::max_threads();
  parallel::set_num_threads(static_cast<int>(state.range(0)));
  FluidParameters<2> p;
  p.l0 = 0.005;
  p.dt = 2e-4;
  p.ppe_tolerance = 1e-8;
  FluidSolver<2, Policies> solver(scenes::dam_break<2>(0.25, 0.5, 1.0, 0.6, p.l0), p);
  solver.advance_to(state.range(1) * 1e-3);
  time_steps(state, solver);
  parallel::set_num_threads(saved);
}

// The same dam break refined to about /particles particles (dam_break_scaled.hpp), from rest
// with two steps before the timed ones, as distributed_step.cpp runs it: the serial side of
// docs/scaling.md's comparison. Arguments: /threads/particles. Also counts the bytes per
// particle that building and running the solver add to the resident set.
template <class Policies>
void dam_break_scaled(benchmark::State& state) {
  const int saved = parallel::max_threads();
  parallel::set_num_threads(static_cast<int>(state.range(0)));
  const bool peak_was_reset = bench::reset_peak_resident_bytes();
  const double resident_before = bench::resident_bytes();
  FluidParameters<2> p;
  p.l0 = bench::dam_break_l0_for(static_cast<double>(state.range(1)));
  p.dt = bench::dam_break_dt_for(p.l0);
  p.ppe_tolerance = 1e-8;
  FluidSolver<2, Policies> solver(scenes::dam_break<2>(0.25, 0.5, 1.0, 0.6, p.l0), p);
  for (int warm = 0; warm < 2; ++warm) solver.step();
  time_steps(state, solver);
  if (peak_was_reset)
    state.counters["bytes/particle"] =
        (bench::peak_resident_bytes() - resident_before) / static_cast<double>(solver.particles().size());
  parallel::set_num_threads(saved);
}

}  // namespace

// /threads/start time in ms (the /1/0 case, from rest, is the CTest smoke run)
BENCHMARK_TEMPLATE(dam_break_step, FluidDefaults<2>)
    ->Args({1, 0})
    ->Args({1, 100})
    ->Args({2, 100})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

// The solver the default (SsorCg) replaced, for comparison.
struct JacobiPolicies : FluidDefaults<2> {
  using linear_solver = JacobiCg;
};
BENCHMARK_TEMPLATE(dam_break_step, JacobiPolicies)->Args({1, 100})->Args({2, 100})->Unit(benchmark::kMillisecond)->UseRealTime();

// SSOR-CG deflated by aggregates.
struct DeflatedPolicies : FluidDefaults<2> {
  using linear_solver = DeflatedSsorCg;
};
BENCHMARK_TEMPLATE(dam_break_step, DeflatedPolicies)
    ->Args({1, 0})
    ->Args({1, 100})
    ->Args({2, 100})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

#if defined(MPSFSI_BENCH_HYPRE)
struct AmgPolicies : FluidDefaults<2> {
  using linear_solver = HypreAmgCg;
};
BENCHMARK_TEMPLATE(dam_break_step, AmgPolicies)->Args({1, 100})->Args({2, 100})->Unit(benchmark::kMillisecond)->UseRealTime();
#endif

// /threads/particles at 1e5 and 1e6 particles, a fixed number of steps each.
BENCHMARK_TEMPLATE(dam_break_scaled, FluidDefaults<2>)
    ->Args({1, 100000})
    ->Args({2, 100000})
    ->Iterations(10)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK_TEMPLATE(dam_break_scaled, FluidDefaults<2>)
    ->Args({1, 1000000})
    ->Args({2, 1000000})
    ->Iterations(3)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK_TEMPLATE(dam_break_scaled, DeflatedPolicies)
    ->Args({1, 100000})
    ->Args({2, 100000})
    ->Iterations(10)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
#if defined(MPSFSI_BENCH_HYPRE)
BENCHMARK_TEMPLATE(dam_break_scaled, AmgPolicies)->Args({1, 100000})->Iterations(10)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_TEMPLATE(dam_break_scaled, AmgPolicies)->Args({1, 1000000})->Iterations(3)->Unit(benchmark::kMillisecond)->UseRealTime();
#endif

BENCHMARK_MAIN();
