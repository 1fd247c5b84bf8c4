// SPDX-License-Identifier: BSD-3-Clause
// Dam break through an elastic gate (Antoci, Gallati & Sibilla 2007): water 0.1 m wide
// and 0.14 m high held by a rubber gate 0.079 m x 0.005 m clamped at its top (rho_s = 1100 kg/m3,
// E = 10 MPa, nu = 0.4), released at t = 0. Writes VTU/PVD of the fluid and the gate, a CSV of
// the gate tip's displacement (with the time step and the fastest fluid particle's speed, which
// sets it), and prints it; plot.py renders the tip history to PNG. Writes checkpoints on request
// and continues from one. `elastic_gate --help` lists the options.
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include <mpsfsi/fluid/fluid_solver.hpp>
#include <mpsfsi/fsi/fsi_coupler.hpp>
#include <mpsfsi/io/checkpoint.hpp>
#include <mpsfsi/io/csv_writer.hpp>
#include <mpsfsi/io/progress.hpp>
#include <mpsfsi/io/pvd_writer.hpp>
#include <mpsfsi/io/vtu_writer.hpp>
#include <mpsfsi/scenes/elastic_gate.hpp>
#include <mpsfsi/solid/elastic_solver.hpp>

#include "common/case_options.hpp"
#include "common/output_folder.hpp"
#include "common/output_record.hpp"
#include "common/run_checkpoints.hpp"

using namespace mpsfsi;

namespace {

struct Options {
  int dim = 2;
  double l0 = 0;        // 0: 1 mm in 2D (5 particles across the gate), 2.5 mm in 3D
  double end = 0.4;     // s
  double every = 0.01;  // s between snapshots
  std::string scheme = "iterated";
  double tolerance = 1e-2;  // sub-iterated coupling: relative change of the interface load
  std::string plane = "strain";
  std::string out = "out/elastic_gate";
  double checkpoint_every = 0;  // s between checkpoints; 0: only on Ctrl-C / SIGTERM
  std::string restart;          // checkpoint to continue from
};

template <int Dim, class Scheme>
int run(const Options& o) {
  const scenes::ElasticGate scene;
  std::vector<std::size_t> clamped;
  std::size_t tip = 0;
  SolidParameters<Dim> sp;
  sp.l0 = o.l0;
  scene.set_material(sp);
  sp.gravity = scene.gravity_vector<Dim>();  // the gate's own weight; y is up in 2D and 3D
  sp.plane_model = o.plane == "strain" ? PlaneModel::plane_strain : PlaneModel::plane_stress;
  ElasticSolver<Dim> gate(scene.gate_particles<Dim>(o.l0, clamped, tip), sp);
  for (auto i : clamped) gate.clamp(i);
  FluidParameters<Dim> fp;
  fp.l0 = o.l0;
  fp.gravity = scene.gravity_vector<Dim>();  // not the default (last axis, z in 3D)
  using Coupler = FsiCoupler<FluidSolver<Dim>, ElasticSolver<Dim>, Scheme>;
  Scheme scheme;
  if constexpr (Scheme::iterative) scheme.tolerance = o.tolerance;
  Coupler coupler(scene.fluid_particles<Dim>(o.l0), fp, std::move(gate), CouplingParameters{}, scheme);

  mpsfsi_examples::make_output_folder(o.out);
  mpsfsi_examples::OutputRecord state;  // rows: gate_tip.csv
  if (!o.restart.empty()) {
    read_checkpoint(o.restart, coupler, state);
    std::printf("continuing from %s: step %lld, t = %g s\n", o.restart.c_str(), coupler.step_count(), coupler.time());
  }
  PvdWriter fluid_pvd(o.out + "/fluid.pvd"), gate_pvd(o.out + "/gate.pvd");
  for (long long k = 0; k < state.frames; ++k) {
    const auto frame = static_cast<std::size_t>(k);
    fluid_pvd.add(state.frame_times[frame], numbered_file_name("fluid", frame));
    gate_pvd.add(state.frame_times[frame], numbered_file_name("gate", frame));
  }
  // dt: the step that led to the row's time; fastest_fluid_speed: the Courant limit's speed.
  const std::vector<std::string> columns = {"t",  "dx", "dy", "interface_force_x", "interface_force_y", "iterations",
                                            "dt", "fastest_fluid_speed"};
  CsvWriter csv = o.restart.empty() ? CsvWriter(o.out + "/gate_tip.csv", columns)
                                    : CsvWriter::continue_after(o.out + "/gate_tip.csv", columns, state.csv_rows);
  mpsfsi_examples::RunCheckpoints checkpoints(o.out, o.checkpoint_every);
  // The tip's position at t = 0, also after a restart.
  const Vec<Dim> tip0 = coupler.solid().reference_positions()[tip];
  std::printf("elastic gate %dD (%s coupling, plane %s): %zu fluid-set particles, %zu gate particles, l0 = %g m, gate "
              "length %.4f m, to t = %g s\n",
              Dim, Scheme::name, o.plane.c_str(), coupler.structure_offset(), coupler.solid().particles().size(), o.l0,
              scene.gate_length_used(o.l0), o.end);
  std::fprintf(stderr, "%s\n", ProgressReporter::legend());
  std::printf("%8s %10s %10s %6s %10s\n", "t (s)", "tip dx (m)", "tip dy (m)", "iter", "max |u| (m/s)");
  ProgressReporter progress(o.end);
  for (;;) {
    const double t = coupler.time();
    // Checkpoints at the top of the loop: a restarted run writes this time's outputs again.
    if (checkpoints.due(t) || checkpoints.stop_requested()) {
      state.csv_rows = csv.rows();
      const std::string path = checkpoints.write(coupler, coupler.step_count(), t, state);
      std::fprintf(stderr, "checkpoint: %s (t = %g s)\n", path.c_str(), t);
      if (checkpoints.stop_requested()) {
        std::fprintf(stderr, "elastic_gate: stopped by a signal; continue with --restart %s\n", path.c_str());
        return checkpoints.stop_exit_code();
      }
    }
    const Vec<Dim> d = coupler.solid().particles().positions()[tip] - tip0;
    const Vec<Dim> f = coupler.total_interface_force();
    const double fastest = coupler.fluid().fastest_fluid_speed();
    csv.row({t, d[0], d[1], f[0], f[1], static_cast<double>(coupler.last_iterations()), coupler.fluid().last_dt(),
             fastest});
    if (t >= state.next_output - 1e-12) {
      const auto frame = static_cast<std::size_t>(state.frames++);
      const std::string ff = numbered_file_name("fluid", frame), gf = numbered_file_name("gate", frame);
      write_vtu(o.out + "/" + ff, coupler.fluid().particles());
      write_vtu(o.out + "/" + gf, coupler.solid().output());
      fluid_pvd.add(t, ff);
      gate_pvd.add(t, gf);
      state.frame_times.push_back(t);
      std::printf("%8.4f %10.5f %10.5f %6d %10.3f\n", t, d[0], d[1], coupler.last_iterations(), fastest);
      state.next_output += o.every;
    }
    if (t >= o.end - 1e-12) break;
    coupler.step();
    progress.update(coupler.step_count(), coupler.time());
  }
  progress.finish();
  std::printf("wall time: fluid %.1f s, gate %.1f s\n", coupler.fluid_seconds(), coupler.solid_seconds());
  std::printf("wrote %s/{fluid,gate}.pvd and %s/gate_tip.csv; plot with python3 examples/elastic_gate/plot.py %s\n",
              o.out.c_str(), o.out.c_str(), o.out.c_str());
  return 0;
}

template <int Dim>
int run_scheme(const Options& o) {
  return o.scheme == "iterated" ? run<Dim, SubIterated>(o) : run<Dim, ExplicitPartitioned>(o);
}

}  // namespace

int main(int argc, char** argv) try {
  Options o;
  mpsfsi_examples::CaseOptions cli("elastic_gate", "Dam break through an elastic gate (Antoci, Gallati & Sibilla 2007)");
  using mpsfsi_examples::one_of;
  using mpsfsi_examples::positive;
  cli.add("--dim", o.dim, "dimension (3: the 2D case extruded 0.02 m between side walls)")->check(one_of({"2", "3"}));
  cli.add("--l0", o.l0, "particle spacing; 0: 0.001 in 2D, 0.0025 in 3D", "m")->check(mpsfsi_examples::non_negative());
  cli.add("--end", o.end, "end time", "s")->check(positive());
  cli.add("--every", o.every, "interval between snapshots", "s")->check(positive());
  cli.add("--scheme", o.scheme, "coupling scheme: sub-iterated (Aitken) or explicit")->check(one_of({"iterated", "explicit"}));
  cli.add("--tolerance", o.tolerance, "sub-iterations' convergence: relative change of the interface load")->check(positive());
  cli.add("--plane", o.plane, "2D plane model of the gate")->check(one_of({"strain", "stress"}));
  cli.add("--checkpoint-every", o.checkpoint_every,
          "simulated time between checkpoints (out/checkpoint_<step>.bin); 0: only on Ctrl-C / SIGTERM", "s")
      ->check(mpsfsi_examples::non_negative());
  cli.add("--restart", o.restart, "checkpoint to continue from (written by a run with the same options)");
  cli.add("--out", o.out, "output folder");
  if (const auto code = cli.parse_or_exit_code(argc, argv)) return *code;
  if (o.l0 == 0) o.l0 = o.dim == 2 ? 0.001 : 0.0025;
  if (cli.print_case_if_requested()) return 0;
  mpsfsi_examples::make_output_folder(o.out);
  cli.write_case(o.out);
  return o.dim == 2 ? run_scheme<2>(o) : run_scheme<3>(o);
} catch (const mpsfsi::SimulationError& e) {
  std::fprintf(stderr, "elastic_gate: %s\n(the last good snapshot is the last one in the .pvd files)\n", e.what());
  return 1;
} catch (const mpsfsi::Error& e) {
  std::fprintf(stderr, "elastic_gate: %s\n", e.what());
  return 1;
}
