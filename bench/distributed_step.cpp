// SPDX-License-Identifier: BSD-3-Clause
// One DistributedFluidSolver step of the 2D dam break refined to about /particles particles
// (dam_break_scaled.hpp; docs/scaling.md), under mpirun. Every process runs the same fixed number
// of iterations (Google Benchmark's own choice could differ between processes and leave one
// waiting in a collective); a step's time is the slowest process's, and process 0 reports. The
// solver starts from rest and takes two steps before the timed ones, so that the PPE starts warm
// as it does in a run.
// Counters: particles, particle-steps/s; milliseconds a step per phase, and of the distribution's
// migration (with rebalancing), halo build and neighbour search (slowest process); the
// PPE's unknowns, CG iterations and its split into matrix, AMG set-up and CG iterations; what the
// busiest process sends a step (halo bytes and messages, particles migrated) and its ghosts;
// memory: the largest process's peak resident set, and the bytes per particle that building
// and running the solver add (peak minus the resident set before the scene was built, summed
// over the processes, over the particle count).
#include <benchmark/benchmark.h>
#include <mpi.h>

#include <algorithm>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "dam_break_scaled.hpp"
#include "mpsfsi/mpi/distributed_fluid_solver.hpp"
#include "mpsfsi/scenes/dam_break.hpp"

using namespace mpsfsi;

namespace {

void dam_break_distributed(benchmark::State& state) {
  const Communicator comm;
  const double l0 = bench::dam_break_l0_for(static_cast<double>(state.range(0)));
  const bool peak_was_reset = comm.min(bench::reset_peak_resident_bytes() ? 1 : 0) == 1;
  const double resident_before = bench::resident_bytes();
  FluidParameters<2> p;
  p.l0 = l0;
  p.dt = bench::dam_break_dt_for(l0);
  p.ppe_tolerance = 1e-8;
  auto mine = scenes::dam_break_part<2>(0.25, 0.5, 1.0, 0.6, l0, 0.0, comm.rank(), comm.size());
  mine.number_ids_from(static_cast<Index>(comm.exclusive_prefix_sum(static_cast<std::int64_t>(mine.size()))));
  DistributedFluidSolver<2> solver(comm, std::move(mine), p);
  for (int warm = 0; warm < 2; ++warm) solver.step();
  if (state.range(1) != 0) solver.rebalance_threshold = -1;  // recut the boxes at every step

  // Per step, the largest value over the processes of: the step, its five phases, the PPE's
  // matrix, set-up and CG, halo bytes, halo messages, migrated particles, ghosts, and the
  // distribution's migration, halo and search.
  std::vector<double> slowest(16), sum(16, 0.0);
  double iterations = 0;
  for (auto _ : state) {
    MPI_Barrier(comm.get());
    const double start = MPI_Wtime();
    solver.step();
    const double seconds = MPI_Wtime() - start;
    const DistributedStepTimings& t = solver.last_timings();
    const auto& ppe = solver.linear_solver().last_timings();
    const DistributedStepTraffic& traffic = solver.last_traffic();
    slowest = {seconds,
               t.distribute,
               t.predictor,
               t.ppe_assembly,
               t.ppe_solve,
               t.corrector,
               ppe.matrix,
               ppe.setup,
               ppe.solve,
               static_cast<double>(traffic.halo_bytes),
               static_cast<double>(traffic.halo_messages),
               static_cast<double>(traffic.migrated),
               static_cast<double>(traffic.ghosts),
               t.migration,
               t.halo,
               t.search};
    comm.max_in_place(slowest);
    state.SetIterationTime(slowest[0]);
    for (std::size_t k = 0; k < sum.size(); ++k) sum[k] += slowest[k];
    iterations += solver.last_solve().iterations;
  }
  const auto unknowns = static_cast<double>(comm.sum(static_cast<std::int64_t>(solver.ppe_rows())));  // last step's
  const auto particles = static_cast<double>(comm.sum(static_cast<std::int64_t>(solver.owned())));
  const double peak = bench::peak_resident_bytes();
  const double largest_peak = comm.max(peak), added = comm.sum(peak - resident_before);

  const double steps = static_cast<double>(state.iterations());
  state.counters["processes"] = comm.size();
  state.counters["particles"] = particles;
  state.counters["particle-steps/s"] = benchmark::Counter(particles, benchmark::Counter::kIsIterationInvariantRate);
  const char* phases[] = {"distribute_ms", "predictor_ms",  "assembly_ms",  "solve_ms",
                          "corrector_ms",  "amg_matrix_ms", "amg_setup_ms", "amg_cg_ms"};
  for (std::size_t k = 1; k < 9; ++k) state.counters[phases[k - 1]] = 1e3 * sum[k] / steps;
  state.counters["ppe_unknowns"] = unknowns;
  state.counters["cg_iterations"] = iterations / steps;
  state.counters["halo_kB"] = 1e-3 * sum[9] / steps;
  state.counters["halo_messages"] = sum[10] / steps;
  state.counters["migrated"] = sum[11] / steps;
  state.counters["ghosts"] = sum[12] / steps;
  state.counters["migration_ms"] = 1e3 * sum[13] / steps;
  state.counters["halo_ms"] = 1e3 * sum[14] / steps;
  state.counters["search_ms"] = 1e3 * sum[15] / steps;
  if (peak_was_reset) {
    state.counters["peak_MB"] = 1e-6 * largest_peak;
    state.counters["bytes/particle"] = added / particles;
  }
}

// A reporter that writes nothing: processes other than 0 run the benchmarks silently.
class SilentReporter : public benchmark::BenchmarkReporter {
 public:
  bool ReportContext(const Context&) override { return true; }
  void ReportRuns(const std::vector<Run>&) override {}
};

}  // namespace

// /particles (about)/recut: 1 recuts the boxes at every step (rebalance_threshold < 0), to time
// a rebalance. 20,000 is the CTest smoke run.
BENCHMARK(dam_break_distributed)->Args({20000, 0})->Iterations(5)->UseManualTime()->Unit(benchmark::kMillisecond);
BENCHMARK(dam_break_distributed)
    ->Args({100000, 0})
    ->Args({100000, 1})
    ->Iterations(10)
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond);
BENCHMARK(dam_break_distributed)
    ->Args({1000000, 0})
    ->Args({1000000, 1})
    ->Iterations(3)
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond);

int main(int argc, char** argv) {
  MPI_Init(&argc, &argv);
  int rank = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  // Only process 0 writes: the others drop --benchmark_out* and report to a silent reporter.
  // Every process drops --benchmark_enable_random_interleaving: each would shuffle the cases its
  // own way, and the processes would meet in different cases' collective calls.
  std::vector<char*> args(argv, argv + argc);
  const auto starts_with = [](const char* a, const char* prefix) { return std::string(a).rfind(prefix, 0) == 0; };
  args.erase(std::remove_if(args.begin() + 1, args.end(),
                            [&](const char* a) {
                              return starts_with(a, "--benchmark_enable_random_interleaving") ||
                                     (rank != 0 && starts_with(a, "--benchmark_out"));
                            }),
             args.end());
  int count = static_cast<int>(args.size());
  args.push_back(nullptr);
  benchmark::Initialize(&count, args.data());
  SilentReporter silent;
  benchmark::RunSpecifiedBenchmarks(rank == 0 ? nullptr : &silent);
  benchmark::Shutdown();
  MPI_Finalize();
  return 0;
}
