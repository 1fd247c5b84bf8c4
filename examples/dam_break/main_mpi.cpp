// SPDX-License-Identifier: BSD-3-Clause
// The dam break of dam_break (main.cpp) on MPI processes: `mpirun -np N dam_break_mpi`, with
// DistributedFluidSolver (docs/scaling.md). The same options and the same CSV columns; the
// snapshots are parallel VTU files (.pvtu, one .vtu piece per process) indexed by the .pvd.
// Process 0 writes the CSV and prints the progress. Checkpoints are not distributed yet.
#include <mpi.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>

#include <mpsfsi/io/csv_writer.hpp>
#include <mpsfsi/io/progress.hpp>
#include <mpsfsi/io/pvd_writer.hpp>
#include <mpsfsi/mpi/distributed_fluid_solver.hpp>
#include <mpsfsi/mpi/distributed_output.hpp>
#include <mpsfsi/scenes/dam_break.hpp>

#include "common/case_options.hpp"

using namespace mpsfsi;

namespace {

struct Options {
  int dim = 2;
  double l0 = 0;        // 0: 5 mm in 2D, 20 mm in 3D
  double dt = -1;       // negative: 2e-4 s in 2D, automatic in 3D; 0: automatic
  double end = 0.4;     // s
  double every = 0.02;  // s between snapshots
  std::string out = "out/dam_break_mpi";
};

// The tank is built on every process and each keeps every P-th particle (the solver moves them
// to their boxes): a scene generator that builds only its own part would not need the whole
// set, which a run at 1e8 particles must avoid.
template <int Dim>
ParticleSet<Dim> my_share(const Communicator& comm, const ParticleSet<Dim>& all) {
  ParticleSet<Dim> mine;
  for (std::size_t i = static_cast<std::size_t>(comm.rank()); i < all.size(); i += static_cast<std::size_t>(comm.size()))
    mine.add(all.positions()[i], all.kinds()[i], all.velocities()[i]);
  mine.number_ids_from(static_cast<Index>(comm.exclusive_prefix_sum(static_cast<std::int64_t>(mine.size()))));
  return mine;
}

template <int Dim>
int run(const Communicator& comm, const Options& o) {
  const double a = 0.25, g = 9.81;  // column width (m); height 2a; tank 4a x 0.6 m
  const bool root = comm.rank() == 0;
  FluidParameters<Dim> p;
  p.l0 = o.l0;
  p.dt = o.dt;
  const auto all = scenes::dam_break<Dim>(a, 2 * a, 4 * a, 0.6, o.l0, Dim == 3 ? 0.1 : 0.0);
  const std::size_t total = all.size();
  DistributedFluidSolver<Dim> solver(comm, my_share(comm, all), p);
  std::unique_ptr<PvdWriter> pvd;
  std::unique_ptr<CsvWriter> csv;
  std::unique_ptr<ProgressReporter> progress;
  // Process 0 writes the index and the CSV; if it cannot, every process stops (no process may
  // wait for it in a collective call).
  std::string error;
  if (root) {
    try {
      pvd = std::make_unique<PvdWriter>(o.out + "/dam_break.pvd");
      csv = std::make_unique<CsvWriter>(o.out + "/dam_break.csv", std::vector<std::string>{"t", "T", "Z_over_a", "tau",
                                                                                            "H_over_2a", "ppe_iterations",
                                                                                            "wall_s"});
    } catch (const Error& e) {
      error = e.what();
    }
  }
  comm.throw_if_any_failed(error);
  if (root) {
    progress = std::make_unique<ProgressReporter>(o.end);
    const std::string dt_text =
        o.dt > 0 ? mpsfsi_examples::detail::format_number(o.dt) + " s" : "automatic (Courant 0.2)";
    std::printf("dam break %dD on %d processes: %zu particles, l0 = %g m, dt = %s, to t = %g s\n", Dim, comm.size(), total,
                o.l0, dt_text.c_str(), o.end);
    std::printf("columns: simulated time; T = t sqrt(2 g / a) and surge front Z/a (Martin & Moyce's scaling); "
                "tau = t sqrt(g / a) and residual column height H/2a\n");
    std::fprintf(stderr, "%s\n", ProgressReporter::legend());
    std::printf("%8s %8s %8s %8s %8s\n", "t (s)", "T", "Z/a", "tau", "H/2a");
  }
  double next_output = 0, wall = 0;
  long long frames = 0, ppe_iterations = 0;
  DistributedStepTimings phases;  // summed over the steps, slowest process per phase
  for (;;) {
    const double t = solver.time();
    if (t >= next_output - 1e-12) {
      const std::string file =
          write_distributed_vtu(comm, o.out, "dam_break_" + std::to_string(frames++), solver.particles());
      const double z = comm.max(scenes::surge_front(solver.particles(), o.l0)) / a;
      const double h = comm.max(scenes::column_height(solver.particles(), o.l0)) / (2 * a);
      if (root) {
        try {
          pvd->add(t, file);
          csv->row({t, t * std::sqrt(2 * g / a), z, t * std::sqrt(g / a), h,
                    static_cast<double>(solver.last_solve().iterations), wall});
        } catch (const Error& e) {
          error = e.what();
        }
      }
      comm.throw_if_any_failed(error);
      if (root) {
        std::printf("%8.4f %8.3f %8.3f %8.3f %8.3f\n", t, t * std::sqrt(2 * g / a), z, t * std::sqrt(g / a), h);
      }
      next_output += o.every;
    }
    if (t >= o.end - 1e-12) break;
    solver.step();
    const DistributedStepTimings& last = solver.last_timings();
    phases.distribute += comm.max(last.distribute);
    phases.predictor += comm.max(last.predictor);
    phases.ppe_assembly += comm.max(last.ppe_assembly);
    phases.ppe_solve += comm.max(last.ppe_solve);
    phases.corrector += comm.max(last.corrector);
    ppe_iterations += solver.last_solve().iterations;
    wall += comm.max(last.total());
    if (root) progress->update(solver.step_count(), solver.time());
  }
  if (root) {
    progress->finish();
    const double steps = static_cast<double>(std::max(1LL, solver.step_count()));
    std::printf("ms per step (slowest process): distribution and search %.2f, predictor %.2f, PPE assembly %.2f, "
                "PPE solve %.2f (%.1f BoomerAMG-PCG iterations), corrector %.2f\n",
                1e3 * phases.distribute / steps, 1e3 * phases.predictor / steps, 1e3 * phases.ppe_assembly / steps,
                1e3 * phases.ppe_solve / steps, static_cast<double>(ppe_iterations) / steps, 1e3 * phases.corrector / steps);
    std::printf("wrote %s/dam_break.pvd and %s/dam_break.csv; plot with python3 examples/dam_break/plot.py %s\n",
                o.out.c_str(), o.out.c_str(), o.out.c_str());
  }
  return 0;
}

int run_main(int argc, char** argv) {
  const Communicator comm;
  Options o;
  mpsfsi_examples::CaseOptions cli("dam_break_mpi", "Dam break of a water column (Martin & Moyce 1952) on MPI processes");
  using mpsfsi_examples::positive;
  cli.add("--dim", o.dim, "dimension")->check(mpsfsi_examples::one_of({"2", "3"}));
  cli.add("--l0", o.l0, "particle spacing; 0: 0.005 in 2D, 0.02 in 3D", "m")->check(mpsfsi_examples::non_negative());
  cli.add("--dt", o.dt, "time step; 0: automatic (Courant 0.2); negative: 2e-4 in 2D, automatic in 3D", "s");
  cli.add("--end", o.end, "end time", "s")->check(positive());
  cli.add("--every", o.every, "interval between snapshots", "s")->check(positive());
  cli.add("--out", o.out, "output folder");
  // Every process parses the same command line, so all stop together on a bad option.
  if (const auto code = cli.parse_or_exit_code(argc, argv)) return *code;
  if (o.l0 == 0) o.l0 = o.dim == 2 ? 0.005 : 0.02;
  if (o.dt < 0) o.dt = o.dim == 2 ? 2e-4 : 0.0;
  if (cli.print_case_if_requested()) return 0;
  std::string error;
  if (comm.rank() == 0) {
    try {
      std::filesystem::create_directories(o.out);
      cli.write_case(o.out);
    } catch (const std::exception& e) {
      error = e.what();
    }
  }
  comm.throw_if_any_failed(error);
  return o.dim == 2 ? run<2>(comm, o) : run<3>(comm, o);
}

}  // namespace

int main(int argc, char** argv) {
  MPI_Init(&argc, &argv);
  int rank = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  int code = 0;
  try {
    code = run_main(argc, argv);
  } catch (const mpsfsi::SimulationError& e) {
    // Every process has the same message; one prints it.
    if (rank == 0) std::fprintf(stderr, "dam_break_mpi: %s\n(the last good snapshot is the last one in the .pvd)\n", e.what());
    code = 1;
  } catch (const mpsfsi::Error& e) {
    if (rank == 0) std::fprintf(stderr, "dam_break_mpi: %s\n", e.what());
    code = 1;
  }
  MPI_Finalize();
  return code;
}
