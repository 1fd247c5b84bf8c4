// SPDX-License-Identifier: BSD-3-Clause
// ElasticSolver throughput: one whole step of a block of material with every particle
// free and the first-mode velocity field of a clamped plate (so every bond is stretched), in
// bond evaluations per second: directed bonds (each pair counted from both ends) times steps.
// Arguments: /particles along the long side/threads. Target: >= 2e8 bond evaluations per
// second per core in 2D, double precision.
#include <benchmark/benchmark.h>

#include <cmath>
#include <cstdint>
#include <vector>

#include "mpsfsi/core/parallel.hpp"
#include "bench_plate.hpp"
#include "mpsfsi/kernels/lattice_constants.hpp"
#include "mpsfsi/solid/bond_viscosity.hpp"
#include "mpsfsi/solid/corrected_total_lagrangian.hpp"
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

// The default stress model's forces with the bond viscosity (what a step with fracture computes),
// on the same plate deformed along its first mode: in one pass over the bonds (Fused) or as the
// model's forces followed by BondViscosity's own pass (as for a model without the fused form).
template <int Dim, bool Fused>
void solid_forces(benchmark::State& state) {
  const int saved = parallel::max_threads();
  parallel::set_num_threads(static_cast<int>(state.range(1)));
  bench::BenchPlate<Dim> plate(state.range(0));
  const auto& p = plate.params;
  BondList<Dim> bonds;
  const std::vector<std::int32_t> one_body(plate.particles.size(), 0);
  bonds.template build<KoshizukaWeight>(plate.particles.positions(), one_body, p.re());
  const auto lattice = ideal_lattice_constants<Dim, KoshizukaWeight>(p.l0, p.re());
  const SolidModelContext<Dim> context{p.lame(), p.density, p.l0, std::pow(p.l0, Dim), lattice.n0, lattice.lambda};
  CorrectedTotalLagrangian<Dim> model;
  model.initialize(bonds, context);
  BondViscosity<Dim> viscosity;
  viscosity.initialize(bonds);
  const double coefficient = SolidParameters<Dim>::fracture_bond_viscosity * p.density * p.p_wave_speed() *
                             context.volume * Dim / context.n0;
  const auto& v = plate.particles.velocities();
  VecArray<Dim> x = plate.particles.positions();
  for (std::size_t i = 0; i < x.size(); ++i) x[i] += 1e-3 * v[i];  // bent along the first mode
  VecArray<Dim> force;
  MatArray<Dim> stress;
  for (auto _ : state) {
    if constexpr (Fused) {
      model.internal_forces(x, v, bonds, force, &stress, coefficient);
    } else {
      model.internal_forces(x, bonds, force, stress);
      viscosity.add(bonds, x, v, coefficient, force);
    }
    benchmark::DoNotOptimize(force.data());
  }
  parallel::set_num_threads(saved);
  const auto directed = static_cast<double>(bonds.num_bonds());
  state.counters["particles"] = static_cast<double>(x.size());
  state.counters["bond_evals/s"] = benchmark::Counter(directed, benchmark::Counter::kIsIterationInvariantRate);
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
BENCHMARK_TEMPLATE(solid_forces, 2, true)->Args({100, 1})->Args({400, 1})->Args({400, 2})->Unit(benchmark::kMicrosecond)->UseRealTime();
BENCHMARK_TEMPLATE(solid_forces, 2, false)->Args({400, 1})->Args({400, 2})->Unit(benchmark::kMicrosecond)->UseRealTime();
BENCHMARK_TEMPLATE(solid_forces, 3, true)->Args({100, 1})->Args({200, 1})->Args({200, 2})->Unit(benchmark::kMicrosecond)->UseRealTime();
BENCHMARK_TEMPLATE(solid_forces, 3, false)->Args({200, 1})->Args({200, 2})->Unit(benchmark::kMicrosecond)->UseRealTime();
BENCHMARK_MAIN();
