// SPDX-License-Identifier: BSD-3-Clause
// Pressure Poisson equation: assembly into CSR (N = 1e3 .. 1e6, 2D and 3D, 1 and 2 threads) and
// solve per linear-solver policy, on a jittered fluid block in an open tank with the Laplacian
// radius 3.1 l0. Arguments: /N/threads.
#include <benchmark/benchmark.h>

#include <cmath>

#include "mpsfsi/core/cell_list_search.hpp"
#include "mpsfsi/core/filter_neighbors.hpp"
#include "mpsfsi/core/parallel.hpp"
#include "mpsfsi/fluid/free_surface.hpp"
#include "mpsfsi/fluid/linear_solver.hpp"
#include "mpsfsi/fluid/ssor_cg.hpp"
#include "mpsfsi/fluid/ppe.hpp"
#include "mpsfsi/kernels/number_density.hpp"
#include "mpsfsi/scenes/lattice.hpp"
#include "mpsfsi/scenes/tank.hpp"
#if defined(MPSFSI_BENCH_HYPRE)
#include "mpsfsi/fluid/hypre_amg.hpp"
#endif

using namespace mpsfsi;

namespace {

// A PPE of about n unknowns: a fluid cube/square in a tank, with a hydrostatic-like source.
template <int Dim>
struct PpeCase {
  ParticleSet<Dim> set;
  NeighborList list;
  std::vector<double> n, source;
  std::vector<std::uint8_t> surface;
  MpsConstants<double> lap;

  explicit PpeCase(std::int64_t target) {
    const double l0 = 1.0;
    const double side = std::round(std::pow(static_cast<double>(target), 1.0 / Dim));
    scenes::add_block<Dim, double>(set, Vec<Dim>::Zero(), Vec<Dim>::Constant(side), l0, ParticleKind::fluid);
    scenes::add_tank<Dim, double>(set, Vec<Dim>::Constant(side), l0);
    for (std::size_t i = 0; i < set.size(); ++i)
      if (set.kinds()[i] == ParticleKind::fluid)
        for (int k = 0; k < Dim; ++k) set.positions()[i][k] += 0.05 * std::sin(37.0 * static_cast<double>(i) + k);
    const double re = 3.1 * l0;
    lap = ideal_lattice_constants<Dim, KoshizukaWeight>(l0, re);
    CellListSearch<Dim> search(re);
    search.build(set.positions());
    NeighborList all;
    QueryOptions opt;
    opt.store_distances = true;
    search.self_query(set.positions(), all, opt);
    const auto& kind = set.kinds();
    filter_neighbors(all, [&](Index j) { return kind[static_cast<std::size_t>(j)] != ParticleKind::dummy; }, list);
    number_density<KoshizukaWeight>(set.positions(), all, re, n);
    // The neighbour-count test: with n < 0.97 n0 alone, the perturbation flags interior particles
    // as free surface, and those Dirichlet rows make the PPE artificially easy.
    NeighborCountSurface::detect(set.positions(), set.kinds(), all, n, lap.n0, 0.97, l0, re, surface);
    source.resize(set.size());
    for (std::size_t i = 0; i < set.size(); ++i) source[i] = -1.0;  // uniform: lap P = -1
  }

  PpeAssembler<KoshizukaWeight, Dim, double> ppe;
  PpeMatrix a;
  PpeVector b;

  void assemble() { ppe.assemble(set.positions(), set.kinds(), surface, list, lap, source, a, b); }
};

template <int Dim>
void assemble(benchmark::State& state) {
  PpeCase<Dim> c(state.range(0));
  const int saved = parallel::max_threads();
  parallel::set_num_threads(static_cast<int>(state.range(1)));
  c.assemble();  // warm-up
  for (auto _ : state) {
    c.assemble();
    benchmark::DoNotOptimize(c.a.valuePtr());
  }
  parallel::set_num_threads(saved);
  const auto rows = static_cast<double>(c.ppe.num_unknowns());
  state.counters["unknowns"] = rows;
  state.counters["nnz/row"] = static_cast<double>(c.a.nonZeros()) / rows;
  state.counters["rows/s"] = benchmark::Counter(rows, benchmark::Counter::kIsIterationInvariantRate);
}

template <int Dim, class Solver>
void solve(benchmark::State& state) {
  PpeCase<Dim> c(state.range(0));
  const int saved = parallel::max_threads();
  parallel::set_num_threads(static_cast<int>(state.range(1)));
  c.assemble();
  const PpeMatrix& a = c.a;
  const PpeVector& b = c.b;
  Solver solver;
  SolveReport report;
  for (auto _ : state) {
    PpeVector x = PpeVector::Zero(b.size());  // cold start: the iteration count of a full solve
    report = solver.solve(a, b, x, 1e-8, 100000);
    benchmark::DoNotOptimize(x.data());
  }
  parallel::set_num_threads(saved);
  state.counters["unknowns"] = static_cast<double>(c.ppe.num_unknowns());
  state.counters["iterations"] = report.iterations;
  state.counters["converged"] = report.converged ? 1 : 0;
}

void assembly_sizes(benchmark::internal::Benchmark* b) {
  for (std::int64_t n : {1000, 10000, 100000, 1000000})
    for (std::int64_t t : {1, 2}) b->Args({n, t});
  b->Unit(benchmark::kMillisecond)->UseRealTime();
}

void solve_sizes(benchmark::internal::Benchmark* b) {
  for (std::int64_t n : {1000, 10000, 100000})
    for (std::int64_t t : {1, 2}) b->Args({n, t});
  b->Unit(benchmark::kMillisecond)->UseRealTime();
}

}  // namespace

BENCHMARK_TEMPLATE(assemble, 2)->Apply(assembly_sizes);
BENCHMARK_TEMPLATE(assemble, 3)->Apply(assembly_sizes);
BENCHMARK_TEMPLATE(solve, 2, JacobiCg)->Apply(solve_sizes);
BENCHMARK_TEMPLATE(solve, 2, SsorCg)->Apply(solve_sizes);
BENCHMARK_TEMPLATE(solve, 2, DeflatedSsorCg)->Apply(solve_sizes);
BENCHMARK_TEMPLATE(solve, 2, EigenJacobiCg)->Apply(solve_sizes);
BENCHMARK_TEMPLATE(solve, 2, IncompleteCholeskyCg)->Apply(solve_sizes);
BENCHMARK_TEMPLATE(solve, 3, JacobiCg)->Apply(solve_sizes);
BENCHMARK_TEMPLATE(solve, 3, SsorCg)->Apply(solve_sizes);
BENCHMARK_TEMPLATE(solve, 3, DeflatedSsorCg)->Apply(solve_sizes);
BENCHMARK_TEMPLATE(solve, 3, IncompleteCholeskyCg)->Apply(solve_sizes);

#if defined(MPSFSI_BENCH_HYPRE)
BENCHMARK_TEMPLATE(solve, 2, HypreAmgCg)->Apply(solve_sizes);
BENCHMARK_TEMPLATE(solve, 3, HypreAmgCg)->Apply(solve_sizes);
#endif

BENCHMARK_MAIN();
