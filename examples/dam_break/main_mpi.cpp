// SPDX-License-Identifier: BSD-3-Clause
// The dam break of dam_break (main.cpp) on MPI processes: `mpirun -np N dam_break_mpi`, with
// DistributedFluidSolver (docs/scaling.md). The same options and the same CSV columns; the
// snapshots are parallel VTU files (.pvtu, one .vtu piece per process) indexed by the .pvd.
// Process 0 writes the CSV and prints the progress. Checkpoints: one file per process
// (<out>/checkpoint_<step>_p<rank>.bin); a run continues from them on as many processes.
#include <mpi.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include <mpsfsi/io/checkpoint.hpp>
#include <mpsfsi/io/csv_writer.hpp>
#include <mpsfsi/io/progress.hpp>
#include <mpsfsi/io/pvd_writer.hpp>
#include <mpsfsi/mpi/distributed_fluid_solver.hpp>
#include <mpsfsi/mpi/distributed_output.hpp>
#include <mpsfsi/scenes/dam_break.hpp>

#include "common/case_options.hpp"
#include "common/output_folder.hpp"
#include "common/run_checkpoints.hpp"
#include "output_state.hpp"

using namespace mpsfsi;

namespace {

struct Options {
  int dim = 2;
  double l0 = 0;        // 0: 5 mm in 2D, 20 mm in 3D
  double dt = -1;       // negative: 2e-4 s in 2D, automatic in 3D; 0: automatic
  double end = 0.4;     // s
  double every = 0.02;  // s between snapshots
  double checkpoint_every = 0;  // s between checkpoints; 0: only on Ctrl-C / SIGTERM
  std::string restart;          // checkpoint to continue from
  std::string out = "out/dam_break_mpi";
};

// This process's part of the scene (the water column's rows dealt out in bands, the tank on
// process 0): no process builds the whole set. The solver moves the particles to their boxes.
template <int Dim>
ParticleSet<Dim> my_part(const Communicator& comm, double a, double l0) {
  auto mine = scenes::dam_break_part<Dim>(a, 2 * a, 4 * a, 0.6, l0, Dim == 3 ? 0.1 : 0.0, comm.rank(), comm.size());
  mine.number_ids_from(static_cast<Index>(comm.exclusive_prefix_sum(static_cast<std::int64_t>(mine.size()))));
  return mine;
}

using dam_break_example::OutputState;

// The file of this process in a checkpoint: <stem>_p<rank>.bin. --restart takes the stem, or
// any one of the files.
std::string checkpoint_piece(std::string stem, int rank) {
  const std::size_t at = stem.rfind("_p");
  if (stem.size() > 4 && stem.compare(stem.size() - 4, 4, ".bin") == 0 && at != std::string::npos &&
      at + 2 < stem.size() - 4 &&
      stem.find_first_not_of("0123456789", at + 2) == stem.size() - 4)
    stem.resize(at);
  return stem + "_p" + std::to_string(rank) + ".bin";
}

template <int Dim>
int run(const Communicator& comm, const Options& o) {
  const double a = 0.25, g = 9.81;  // column width (m); height 2a; tank 4a x 0.6 m
  const bool root = comm.rank() == 0;
  FluidParameters<Dim> p;
  p.l0 = o.l0;
  p.dt = o.dt;
  auto mine = my_part<Dim>(comm, a, o.l0);
  const auto total = static_cast<std::size_t>(comm.sum(static_cast<std::int64_t>(mine.size())));
  DistributedFluidSolver<Dim> solver(comm, std::move(mine), p);
  OutputState state;
  // Each process reads its own file; if any cannot, every process stops with its message.
  std::string error;
  if (!o.restart.empty()) {
    try {
      read_checkpoint(checkpoint_piece(o.restart, comm.rank()), solver, state);
    } catch (const Error& e) {
      error = e.what();
    }
    comm.throw_if_any_failed(error);
    solver.check_checkpoint_pieces();
    if (root)
      std::printf("continuing from %s: step %lld, t = %g s\n", checkpoint_piece(o.restart, 0).c_str(), solver.step_count(),
                  solver.time());
  }
  std::unique_ptr<PvdWriter> pvd;
  std::unique_ptr<CsvWriter> csv;
  std::unique_ptr<ProgressReporter> progress;
  // Process 0 writes the index and the CSV; if it cannot, every process stops (no process may
  // wait for it in a collective call).
  const std::vector<std::string> columns = {"t", "T", "Z_over_a", "tau", "H_over_2a", "ppe_iterations", "wall_s"};
  if (root) {
    try {
      pvd = std::make_unique<PvdWriter>(o.out + "/dam_break.pvd");
      for (long long k = 0; k < state.frames; ++k)
        pvd->add(state.frame_times[static_cast<std::size_t>(k)], "dam_break_" + std::to_string(k) + ".pvtu");
      csv = std::make_unique<CsvWriter>(
          o.restart.empty() ? CsvWriter(o.out + "/dam_break.csv", columns)
                            : CsvWriter::continue_after(o.out + "/dam_break.csv", columns, state.csv_rows));
    } catch (const Error& e) {
      error = e.what();
    }
  }
  comm.throw_if_any_failed(error);
  mpsfsi_examples::RunCheckpoints checkpoints(o.out, o.checkpoint_every, "checkpoint",
                                              "_p" + std::to_string(comm.rank()));
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
  long long steps = 0, ppe_iterations = 0;  // in this run
  DistributedStepTimings phases;  // summed over this run's steps, slowest process per phase
  double halo_bytes = 0, halo_messages = 0, migrated = 0;  // summed over this run's steps, busiest process
  std::vector<double> slowest;
  for (;;) {
    const double t = solver.time();
    if (t >= state.next_output - 1e-12) {
      const std::string file =
          write_distributed_vtu(comm, o.out, "dam_break_" + std::to_string(state.frames++), solver.particles());
      state.frame_times.push_back(t);
      const double z = comm.max(scenes::surge_front(solver.particles(), o.l0)) / a;
      const double h = comm.max(scenes::column_height(solver.particles(), o.l0)) / (2 * a);
      if (root) {
        try {
          pvd->add(t, file);
          csv->row({t, t * std::sqrt(2 * g / a), z, t * std::sqrt(g / a), h,
                    static_cast<double>(solver.last_solve().iterations), state.wall});
          state.csv_rows = csv->rows();
        } catch (const Error& e) {
          error = e.what();
        }
      }
      comm.throw_if_any_failed(error);
      if (root) std::printf("%8.4f %8.3f %8.3f %8.3f %8.3f\n", t, t * std::sqrt(2 * g / a), z, t * std::sqrt(g / a), h);
      state.next_output += o.every;
    }
    // A signal reaches the processes at different moments: they stop together at the first step
    // at which any has it.
    const int stop_code = comm.max(checkpoints.stop_requested() ? checkpoints.stop_exit_code() : 0);
    if (checkpoints.due(t) || stop_code != 0) {
      std::string path;
      try {
        path = checkpoints.write(solver, solver.step_count(), t, state);
      } catch (const Error& e) {
        error = e.what();
      }
      comm.throw_if_any_failed(error);
      const std::string stem = path.substr(0, path.size() - checkpoint_piece("", comm.rank()).size());
      if (root) std::fprintf(stderr, "checkpoint: %s_p*.bin (t = %g s)\n", stem.c_str(), t);
      if (stop_code != 0) {
        if (root) std::fprintf(stderr, "dam_break_mpi: stopped by a signal; continue with --restart %s\n", stem.c_str());
        return stop_code;
      }
    }
    if (t >= o.end - 1e-12) break;
    solver.step();
    ++steps;
    const DistributedStepTimings& last = solver.last_timings();
    const DistributedStepTraffic& traffic = solver.last_traffic();
    slowest = {last.distribute, last.predictor, last.ppe_assembly, last.ppe_solve, last.corrector, last.total(),
               static_cast<double>(traffic.halo_bytes), static_cast<double>(traffic.halo_messages),
               static_cast<double>(traffic.migrated)};
    comm.max_in_place(slowest);
    phases.distribute += slowest[0];
    phases.predictor += slowest[1];
    phases.ppe_assembly += slowest[2];
    phases.ppe_solve += slowest[3];
    phases.corrector += slowest[4];
    state.wall += slowest[5];
    halo_bytes += slowest[6];
    halo_messages += slowest[7];
    migrated += slowest[8];
    ppe_iterations += solver.last_solve().iterations;
    if (root) progress->update(solver.step_count(), solver.time());
  }
  if (root) {
    progress->finish();
    const double n = static_cast<double>(std::max(1LL, steps));
    std::printf("ms per step (slowest process): distribution and search %.2f, predictor %.2f, PPE assembly %.2f, "
                "PPE solve %.2f (%.1f BoomerAMG-PCG iterations), corrector %.2f\n",
                1e3 * phases.distribute / n, 1e3 * phases.predictor / n, 1e3 * phases.ppe_assembly / n,
                1e3 * phases.ppe_solve / n, static_cast<double>(ppe_iterations) / n, 1e3 * phases.corrector / n);
    std::printf("sent per step (busiest process): halo %.1f kB in %.1f messages, %.1f particles migrated; "
                "boxes recut %lld times\n",
                1e-3 * halo_bytes / n, halo_messages / n, migrated / n, solver.rebalances());
    std::printf("wrote %s/dam_break.pvd and %s/dam_break.csv; plot with python3 examples/dam_break/plot.py %s\n",
                o.out.c_str(), o.out.c_str(), o.out.c_str());
  }
  return 0;
}

int run_main(int argc, char** argv) {
  const Communicator comm;
  // Process 0 prints for all (--help, --print-case, the table); the others' output would repeat it.
  if (comm.rank() != 0) {
    std::FILE* quiet = std::freopen("/dev/null", "w", stdout);
    (void)quiet;  // if /dev/null cannot be opened, freopen has closed stdout: silent all the same
  }
  Options o;
  mpsfsi_examples::CaseOptions cli("dam_break_mpi", "Dam break of a water column (Martin & Moyce 1952) on MPI processes");
  using mpsfsi_examples::positive;
  cli.add("--dim", o.dim, "dimension")->check(mpsfsi_examples::one_of({"2", "3"}));
  cli.add("--l0", o.l0, "particle spacing; 0: 0.005 in 2D, 0.02 in 3D", "m")->check(mpsfsi_examples::non_negative());
  cli.add("--dt", o.dt, "time step; 0: automatic (Courant 0.2); negative: 2e-4 in 2D, automatic in 3D", "s");
  cli.add("--end", o.end, "end time", "s")->check(positive());
  cli.add("--every", o.every, "interval between snapshots", "s")->check(positive());
  cli.add("--checkpoint-every", o.checkpoint_every,
          "simulated time between checkpoints (out/checkpoint_<step>_p<rank>.bin, one file per process); 0: only on "
          "Ctrl-C / SIGTERM",
          "s")
      ->check(mpsfsi_examples::non_negative());
  cli.add("--restart", o.restart,
          "checkpoint to continue from (out/checkpoint_<step>, or one of its files), written by a run with the same "
          "options on as many processes");
  cli.add("--out", o.out, "output folder");
  // Every process parses the same command line, so all stop together on a bad option.
  if (const auto code = cli.parse_or_exit_code(argc, argv)) return *code;
  if (o.l0 == 0) o.l0 = o.dim == 2 ? 0.005 : 0.02;
  if (o.dt < 0) o.dt = o.dim == 2 ? 2e-4 : 0.0;
  if (cli.print_case_if_requested()) return 0;
  std::string error;
  if (comm.rank() == 0) {
    try {
      mpsfsi_examples::make_output_folder(o.out);
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
