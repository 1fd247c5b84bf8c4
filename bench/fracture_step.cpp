// SPDX-License-Identifier: BSD-3-Clause
// The brittle solid's step and its parts, as the bending study runs them.
// - fracture_step: one whole ElasticSolver step of BrittleSolidPolicies (forces, bond viscosity
//   0.2, the failure check with the stress read at the surface and averaged), on the plate block
//   of the solid_step benchmark with its first-mode velocity field. The strength (1e30 Pa) is
//   out of reach, so the check runs in full at every step but cuts nothing and every step costs
//   the same. The failure model is MaxPrincipalStress, whose convex upper bound lets the check
//   skip the averaging and the eigen-decomposition of every particle here (the strength is out of
//   reach); the same bound not declared convex (BoundPerParticle), which averages every particle
//   and skips the decompositions; or the criterion without the bound (Unscreened), which averages
//   and decomposes every particle's stress. They bracket a real run, where the particles near
//   their strength are averaged and decomposed.
//   Arguments /particles along the long side/threads; particle-steps per second.
// - principal_stress: sigma_1 and its direction for a batch of symmetric stress tensors, by
//   max_principal_stress and, in 3D, by Eigen's iterative self-adjoint solver for comparison.
#include <benchmark/benchmark.h>

#include <random>
#include <vector>

#include <Eigen/Eigenvalues>

#include "mpsfsi/core/parallel.hpp"
#include "mpsfsi/fracture/fracture_process.hpp"
#include "bench_plate.hpp"
#include "mpsfsi/solid/principal_stress.hpp"

using namespace mpsfsi;

namespace {

// MaxPrincipalStress without its upper bound.
struct Unscreened {
  static constexpr bool enabled = true;
  template <int Dim, class Scalar>
  static Scalar principal(const Mat<Dim, Scalar>& sigma, Vec<Dim, Scalar>& direction) {
    return MaxPrincipalStress::principal<Dim, Scalar>(sigma, direction);
  }
};

// MaxPrincipalStress with its bound, not declared convex: the bound screens the
// eigen-decompositions, but the read-out is averaged at every particle.
struct BoundPerParticle {
  static constexpr bool enabled = true;
  template <int Dim, class Scalar>
  static Scalar principal(const Mat<Dim, Scalar>& sigma, Vec<Dim, Scalar>& direction) {
    return MaxPrincipalStress::principal<Dim, Scalar>(sigma, direction);
  }
  template <int Dim, class Scalar>
  static Scalar upper_bound(const Mat<Dim, Scalar>& sigma) {
    return MaxPrincipalStress::upper_bound<Dim, Scalar>(sigma);
  }
};

template <int Dim, class Failure>
struct Policies : BrittleSolidPolicies<Dim> {
  using failure = Failure;
};

template <int Dim, class Failure>
void fracture_step(benchmark::State& state) {
  const int saved = parallel::max_threads();
  parallel::set_num_threads(static_cast<int>(state.range(1)));
  bench::BenchPlate<Dim> plate(state.range(0));
  plate.params.tensile_strength = 1e30;
  ElasticSolver<Dim, Policies<Dim, Failure>> solver(plate.particles, plate.params);
  for (const auto i : plate.clamped) solver.clamp(i);
  for (int k = 0; k < 10; ++k) solver.step();
  for (auto _ : state) solver.step();
  parallel::set_num_threads(saved);
  const auto particles = static_cast<double>(solver.particles().size());
  state.counters["particles"] = particles;
  state.counters["particle-steps/s"] = benchmark::Counter(particles, benchmark::Counter::kIsIterationInvariantRate);
}

// Random symmetric tensors with entries of a stress's size (MPa), a fixed seed.
template <int Dim>
MatArray<Dim, double> random_stresses(std::size_t count) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(-1e6, 1e6);
  MatArray<Dim, double> sigma(count);
  for (auto& s : sigma) {
    for (int a = 0; a < Dim; ++a)
      for (int b = a; b < Dim; ++b) s(a, b) = s(b, a) = u(rng);
  }
  return sigma;
}

constexpr std::size_t kTensors = 4096;

template <int Dim>
void principal_stress(benchmark::State& state) {
  const auto sigma = random_stresses<Dim>(kTensors);
  Vec<Dim, double> direction;
  for (auto _ : state)
    for (const auto& s : sigma) {
      benchmark::DoNotOptimize(max_principal_stress<Dim, double>(s, direction));
      benchmark::DoNotOptimize(direction);
    }
  state.counters["tensors/s"] = benchmark::Counter(double(kTensors), benchmark::Counter::kIsIterationInvariantRate);
}

void principal_stress_eigen_iterative(benchmark::State& state) {
  const auto sigma = random_stresses<3>(kTensors);
  for (auto _ : state)
    for (const auto& s : sigma) {
      Eigen::SelfAdjointEigenSolver<Mat<3, double>> eig(s);
      benchmark::DoNotOptimize(eig.eigenvalues());
      benchmark::DoNotOptimize(eig.eigenvectors());
    }
  state.counters["tensors/s"] = benchmark::Counter(double(kTensors), benchmark::Counter::kIsIterationInvariantRate);
}

}  // namespace

// 2D: 40 x 400 particles; 3D: 10 x 10 x 100 and 20 x 20 x 200 (the 3D bending beam at
// l0 = 2 mm has 77,000).
BENCHMARK_TEMPLATE(fracture_step, 2, MaxPrincipalStress)->Args({100, 1})->Args({400, 1})->Args({400, 2})->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_TEMPLATE(fracture_step, 3, MaxPrincipalStress)->Args({100, 1})->Args({200, 1})->Args({200, 2})->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_TEMPLATE(fracture_step, 2, BoundPerParticle)->Args({400, 1})->Args({400, 2})->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_TEMPLATE(fracture_step, 3, BoundPerParticle)->Args({100, 1})->Args({200, 1})->Args({200, 2})->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_TEMPLATE(fracture_step, 3, Unscreened)->Args({100, 1})->Args({200, 1})->Args({200, 2})->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_TEMPLATE(principal_stress, 2)->Unit(benchmark::kMicrosecond);
BENCHMARK_TEMPLATE(principal_stress, 3)->Unit(benchmark::kMicrosecond);
BENCHMARK(principal_stress_eigen_iterative)->Unit(benchmark::kMicrosecond);
BENCHMARK_MAIN();
