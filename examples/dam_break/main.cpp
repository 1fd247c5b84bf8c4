// SPDX-License-Identifier: BSD-3-Clause
// Dam break (Martin & Moyce 1952; Koshizuka & Oka 1996): a water column a wide and 2a high
// collapses in a tank 4a long. Writes VTU/PVD snapshots, a CSV of the surge front and the
// residual column height, and prints them against the experiment's scaling. `dam_break --help`
// lists the options.
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include <mpsfsi/fluid/fluid_solver.hpp>
#include <mpsfsi/io/checkpoint.hpp>
#include <mpsfsi/io/csv_writer.hpp>
#include <mpsfsi/io/progress.hpp>
#include <mpsfsi/io/pvd_writer.hpp>
#include <mpsfsi/io/vtu_writer.hpp>
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
  std::string out = "out/dam_break";
};

using dam_break_example::OutputState;

template <int Dim>
int run(const Options& o) {
  const double a = 0.25, g = 9.81;  // column width (m); height 2a; tank 4a x 0.6 m
  FluidParameters<Dim> p;
  p.l0 = o.l0;
  p.dt = o.dt;
  FluidSolver<Dim> solver(scenes::dam_break<Dim>(a, 2 * a, 4 * a, 0.6, o.l0, Dim == 3 ? 0.1 : 0.0), p);
  mpsfsi_examples::make_output_folder(o.out);
  OutputState state;
  if (!o.restart.empty()) {
    read_checkpoint(o.restart, solver, state);
    std::printf("continuing from %s: step %lld, t = %g s\n", o.restart.c_str(), solver.step_count(), solver.time());
  }
  PvdWriter pvd(o.out + "/dam_break.pvd");
  for (long long k = 0; k < state.frames; ++k)
    pvd.add(state.frame_times[static_cast<std::size_t>(k)], numbered_file_name("dam_break", static_cast<std::size_t>(k)));
  const std::vector<std::string> columns = {"t", "T", "Z_over_a", "tau", "H_over_2a", "ppe_iterations", "wall_s"};
  CsvWriter csv = o.restart.empty() ? CsvWriter(o.out + "/dam_break.csv", columns)
                                    : CsvWriter::continue_after(o.out + "/dam_break.csv", columns, state.csv_rows);
  mpsfsi_examples::RunCheckpoints checkpoints(o.out, o.checkpoint_every);
  ProgressReporter progress(o.end);
  const std::string dt_text =
      o.dt > 0 ? mpsfsi_examples::detail::format_number(o.dt) + " s" : "automatic (Courant 0.2)";
  std::printf("dam break %dD: %zu particles, l0 = %g m, dt = %s, to t = %g s\n", Dim, solver.particles().size(), o.l0,
              dt_text.c_str(), o.end);
  std::printf("columns: simulated time; T = t sqrt(2 g / a) and surge front Z/a (Martin & Moyce's scaling); "
              "tau = t sqrt(g / a) and residual column height H/2a\n");
  std::fprintf(stderr, "%s\n", ProgressReporter::legend());
  std::printf("%8s %8s %8s %8s %8s\n", "t (s)", "T", "Z/a", "tau", "H/2a");
  for (;;) {
    const double t = solver.time();
    if (t >= state.next_output - 1e-12) {
      const std::string file = numbered_file_name("dam_break", static_cast<std::size_t>(state.frames++));
      write_vtu(o.out + "/" + file, solver.particles());
      pvd.add(t, file);
      state.frame_times.push_back(t);
      const double z = scenes::surge_front(solver.particles(), o.l0) / a;
      const double h = scenes::column_height(solver.particles(), o.l0) / (2 * a);
      csv.row({t, t * std::sqrt(2 * g / a), z, t * std::sqrt(g / a), h,
               static_cast<double>(solver.last_solve().iterations), state.wall});
      std::printf("%8.4f %8.3f %8.3f %8.3f %8.3f\n", t, t * std::sqrt(2 * g / a), z, t * std::sqrt(g / a), h);
      state.next_output += o.every;
    }
    if (checkpoints.due(t) || checkpoints.stop_requested()) {
      state.csv_rows = csv.rows();
      const std::string path = checkpoints.write(solver, solver.step_count(), t, state);
      std::fprintf(stderr, "checkpoint: %s (t = %g s)\n", path.c_str(), t);
      if (checkpoints.stop_requested()) {
        std::fprintf(stderr, "dam_break: stopped by a signal; continue with --restart %s\n", path.c_str());
        return checkpoints.stop_exit_code();
      }
    }
    if (t >= o.end - 1e-12) break;
    solver.step();
    state.wall += solver.last_timings().total();
    progress.update(solver.step_count(), solver.time());
  }
  progress.finish();
  std::printf("wrote %s/dam_break.pvd and %s/dam_break.csv; plot with python3 examples/dam_break/plot.py %s\n", o.out.c_str(),
              o.out.c_str(), o.out.c_str());
  return 0;
}

}  // namespace

int main(int argc, char** argv) try {
  Options o;
  mpsfsi_examples::CaseOptions cli("dam_break", "Dam break of a water column (Martin & Moyce 1952)");
  using mpsfsi_examples::positive;
  cli.add("--dim", o.dim, "dimension")->check(mpsfsi_examples::one_of({"2", "3"}));
  cli.add("--l0", o.l0, "particle spacing; 0: 0.005 in 2D, 0.02 in 3D", "m")->check(mpsfsi_examples::non_negative());
  cli.add("--dt", o.dt, "time step; 0: automatic (Courant 0.2); negative: 2e-4 in 2D, automatic in 3D", "s");
  cli.add("--end", o.end, "end time", "s")->check(positive());
  cli.add("--every", o.every, "interval between snapshots", "s")->check(positive());
  cli.add("--checkpoint-every", o.checkpoint_every,
          "simulated time between checkpoints (out/checkpoint_<step>.bin); 0: only on Ctrl-C / SIGTERM", "s")
      ->check(mpsfsi_examples::non_negative());
  cli.add("--restart", o.restart, "checkpoint to continue from (written by a run with the same options)");
  cli.add("--out", o.out, "output folder");
  if (const auto code = cli.parse_or_exit_code(argc, argv)) return *code;
  if (o.l0 == 0) o.l0 = o.dim == 2 ? 0.005 : 0.02;
  if (o.dt < 0) o.dt = o.dim == 2 ? 2e-4 : 0.0;
  if (cli.print_case_if_requested()) return 0;
  mpsfsi_examples::make_output_folder(o.out);
  cli.write_case(o.out);
  return o.dim == 2 ? run<2>(o) : run<3>(o);
} catch (const mpsfsi::SimulationError& e) {
  std::fprintf(stderr, "dam_break: %s\n(the last good snapshot is the last one in the .pvd)\n", e.what());
  return 1;
} catch (const mpsfsi::Error& e) {
  std::fprintf(stderr, "dam_break: %s\n", e.what());
  return 1;
}
