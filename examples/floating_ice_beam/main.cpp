// SPDX-License-Identifier: BSD-3-Clause
// Floating ice under an end load, on the water's Winkler foundation k = rho_w g
// (docs/validation/fracture.md, "Ice on an elastic foundation"): a long ice beam (h = 40 mm,
// E = 60 MPa, nu = 0.3, sigma_f = 30 kPa; scenes::FloatingIceBeam) loaded at its left end.
// Phase 1 holds P_f / 2 and compares the settled deflection with Hetenyi's semi-infinite beam;
// phase 2 raises the load past the breaking load P_f (Croasdale's breaking term) until the beam
// cracks where Hetenyi's moment is largest, pi / (4 lambda) from the end. The water itself is not
// simulated: a coupled floating beam is not verified yet (docs/validation/fsi.md, open problems).
// Writes the deflection profile against Hetenyi's, the load history, every particle failure and
// VTU/PVD snapshots; plot.py renders the PNGs. `floating_ice_beam --help` lists the options.
#include <cmath>
#include <cstdio>
#include <string>

#include "common/case_options.hpp"
#include "common/output_folder.hpp"
#include "floating_ice_beam/beam_on_foundation.hpp"

namespace {

struct Options {
  double thickness = 0.04;
  int rows = 8;
  std::string fracture = "on";
  std::string out = "out/floating_ice_beam";
  bool no_output = false;
};

}  // namespace

int main(int argc, char** argv) try {
  Options o;
  mpsfsi_examples::CaseOptions cli("floating_ice_beam",
                                   "Floating ice under an end load on a Winkler foundation, against Hetenyi's beam");
  cli.add("--thickness", o.thickness, "ice thickness h", "m")->check(mpsfsi_examples::positive());
  cli.add("--rows", o.rows, "particles through the thickness (h / l0), at least 2");
  cli.add("--fracture", o.fracture, "phase 2: raise the load past P_f until the beam breaks")
      ->check(mpsfsi_examples::one_of({"on", "off"}));
  cli.add("--out", o.out, "output folder");
  cli.flag("--no-output", o.no_output, "write no files");
  if (const auto code = cli.parse_or_exit_code(argc, argv)) return *code;
  if (cli.print_case_if_requested()) return 0;
  if (o.rows < 2) {
    std::fprintf(stderr, "floating_ice_beam: --rows: must be at least 2, not %d\n", o.rows);
    return 2;
  }
  mpsfsi::scenes::FloatingIceBeam scene;
  scene.thickness = o.thickness;
  floating_ice::RunOptions run;
  run.rows = o.rows;
  run.fracture = o.fracture == "on";
  run.out = o.no_output ? std::string() : o.out;
  run.progress = true;
  if (!run.out.empty()) {
    mpsfsi_examples::make_output_folder(run.out);
    cli.write_case(run.out);
  }
  const double l0 = o.thickness / o.rows;
  std::printf("Floating ice beam on a Winkler foundation: h = %g m, l0 = %g m (%d rows), beam %g m, E = %g MPa, "
              "sigma_f = %g kPa\n",
              scene.thickness, l0, o.rows, scene.beam_length_for(l0), scene.youngs_modulus / 1e6,
              scene.tensile_strength / 1e3);
  std::printf("Hetenyi: 1/lambda = %.4f m, pi/(4 lambda) = %.4f m, P_f = %.3f N/m\n", 1 / scene.lambda(),
              scene.largest_moment_position(), scene.failure_load());
  std::fprintf(stderr, "%s\n", mpsfsi::ProgressReporter::legend());
  const auto r = floating_ice::run(scene, run);

  const auto& d = r.deflection;
  std::printf("phase 1, P = P_f/2 = %.3f N/m: end deflection %.4e m, %+.2f %% from Hetenyi's; profile RMS to "
              "3/lambda %.2f %% of it; foundation force / P - 1 = %+.1e\n",
              d.load, d.w[0], 100 * d.end_error, 100 * d.profile_rms, d.balance_error);
  const double x_f = scene.largest_moment_position(), Pf = scene.failure_load();
  const auto& b = r.brk;
  if (run.fracture) {
    if (b.failures == 0) {
      std::printf("phase 2: no failure by t = %g s\n", r.end_time);
    } else {
      const bool top = scene.beam_bottom(l0) + scene.thickness - b.first_failure[1] < l0;
      std::printf("phase 2: first failure at t = %.4f s, x = %.4f m (%+.1f %% from pi/(4 lambda)), %s fibre, P = %.3f N/m "
                  "(%+.1f %% of P_f); %zu failures, %zu bonds cut; %zu pieces of more than 10 particles, %zu particles "
                  "in smaller ones\n",
                  b.first_failure_time, b.first_failure[0], 100 * (b.first_failure[0] / x_f - 1), top ? "top" : "inner",
                  -b.load_at_failure[1], 100 * (-b.load_at_failure[1] / Pf - 1), b.failures, b.cut_bonds, b.pieces,
                  b.small_fragment_particles);
      if (b.pieces >= 2)
        std::printf("phase 2: the far piece from x = %.4f m (%+.1f %% from pi/(4 lambda))\n", b.far_piece_start,
                    100 * (b.far_piece_start / x_f - 1));
    }
  }
  std::printf("summary: end deflection %+.2f %%, profile RMS %.2f %%, balance %+.1e", 100 * d.end_error,
              100 * d.profile_rms, d.balance_error);
  if (b.failures > 0)
    std::printf(", first failure x %+.1f %%, P %+.1f %%, pieces %zu", 100 * (b.first_failure[0] / x_f - 1),
                100 * (-b.load_at_failure[1] / Pf - 1), b.pieces);
  if (b.pieces >= 2) std::printf(", break x %+.1f %%", 100 * (b.far_piece_start / x_f - 1));
  std::printf("; %zu particles, %lld steps, %.1f s on %d threads\n", r.particles, r.steps, r.wall_seconds,
              mpsfsi::parallel::max_threads());
  if (!run.out.empty()) {
    mpsfsi::CsvWriter summary(run.out + "/summary.csv",
                              {"thickness", "l0", "beam_length", "lambda", "failure_load", "largest_moment_x", "end_error",
                               "profile_rms", "balance_error", "failures", "first_failure_x", "first_failure_y",
                               "load_at_failure", "pieces", "far_piece_x", "wall_s"});
    summary.row({scene.thickness, l0, scene.beam_length_for(l0), scene.lambda(), Pf, x_f, d.end_error, d.profile_rms,
                 d.balance_error, static_cast<double>(b.failures), b.first_failure[0], b.first_failure[1],
                 -b.load_at_failure[1], static_cast<double>(b.pieces), b.far_piece_start, r.wall_seconds});
  }
  if (!run.out.empty())
    std::printf("wrote %s (case.yaml reruns this case); plot with python3 examples/floating_ice_beam/plot.py %s\n",
                run.out.c_str(), run.out.c_str());
  return 0;
} catch (const mpsfsi::SimulationError& e) {
  std::fprintf(stderr, "floating_ice_beam: %s\n", e.what());
  return 1;
} catch (const mpsfsi::Error& e) {
  std::fprintf(stderr, "floating_ice_beam: %s\n", e.what());
  return 1;
}
