// SPDX-License-Identifier: BSD-3-Clause
// Floating ice under an end load (scenes::FloatingIceBeam), against Hetenyi's semi-infinite beam
// on the water's Winkler foundation k = rho_w g: the deflection below the breaking load P_f
// (Croasdale's breaking term) and the break past it, where Hetenyi's moment is largest,
// pi / (4 lambda) from the loaded end.
//  --foundation water (the default): the ice floats on the water of its tank, coupled by IQN-ILS
//    (h = 80 mm, 875 kg/m3; docs/validation/fsi.md, "Floating ice beam under an end load"). With
//    fracture the load rises past P_f until the beam breaks, and the profile is compared at
//    0.9 P_f; without, P_f / 2 is held to 30 s and compared then.
//  --foundation springs: the same ice on springs under its bottom row, the water not simulated
//    (h = 40 mm, 917 kg/m3; docs/validation/fracture.md, "Ice on an elastic foundation").
//  --dim 3: on either foundation, a strip of --width (3 h by default) across a channel, under a
//    line load along its end.
// Writes the deflection profile against Hetenyi's, the load history, every particle failure and
// VTU/PVD snapshots (with water: of the ice and the water); plot.py renders the PNGs.
// `floating_ice_beam --help` lists the options.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "common/case_options.hpp"
#include "common/output_folder.hpp"
#include "floating_ice_beam/beam_in_water.hpp"
#include "floating_ice_beam/beam_on_foundation.hpp"

namespace {

struct Options {
  std::string foundation = "water";
  double thickness = 0;  // 0: the foundation's own (0.08 m with water, 0.04 m on springs)
  int rows = 8;
  int dim = 2;
  double width = 0;  // 3D: the strip's width; 0: 3 h
  double ice_density = 0;  // 0: the foundation's own (875 kg/m3 with water, 917 kg/m3 on springs)
  std::string fracture = "on";
  double end_time = 0;  // water only; 0: the protocol's end
  double after_failure = 0.1;  // springs only
  std::string out = "out/floating_ice_beam";
  bool no_output = false;
};

// What both foundations report, for the summary line and summary.csv.
struct Outcome {
  floating_ice::DeflectionCheck deflection;
  floating_ice::BreakResult brk;
  double end_time = 0, wall_seconds = 0, fluid_solves_per_step = 0;
  double fluid_seconds = 0, solid_seconds = 0;  // of wall_seconds; with water only
  double moment_before_load = 0;  // N m/m at pi / (4 lambda); with water only (springs: none)
  double roll = 0, sideways = 0;   // m; the 3D strip in water only (WaterRunResult)
  int most_fluid_solves = 0;
  std::size_t particles = 0, water_particles = 0;
  long long steps = 0;
  std::string error;  // a blow-up's message
};

Outcome run_on_springs(const mpsfsi::scenes::FloatingIceBeam& scene, const Options& o) {
  floating_ice::RunOptions run;
  run.rows = o.rows;
  run.fracture = o.fracture == "on";
  run.after_failure = o.after_failure;
  run.out = o.no_output ? std::string() : o.out;
  run.progress = true;
  std::fprintf(stderr, "%s\n", mpsfsi::ProgressReporter::legend());
  const auto r = o.dim == 3 ? floating_ice::run<3>(scene, run) : floating_ice::run<2>(scene, run);
  Outcome c;
  c.deflection = r.deflection;
  c.brk = r.brk;
  c.end_time = r.end_time;
  c.wall_seconds = r.wall_seconds;
  c.particles = r.particles;
  c.steps = r.steps;
  return c;
}

template <int Dim>
floating_ice::WaterRunResult run_in_water_as(const mpsfsi::scenes::FloatingIceBeam& scene,
                                             const floating_ice::WaterRunSettings& settings,
                                             const floating_ice::EndLoad& load, bool fracture) {
  return fracture ? floating_ice::run_in_water<floating_ice::IceSolverOf<Dim>>(scene, settings, load)
                  : floating_ice::run_in_water<mpsfsi::ElasticSolver<Dim>>(scene, settings, load);
}

Outcome run_in_water(const mpsfsi::scenes::FloatingIceBeam& scene, const Options& o) {
  const double l0 = scene.thickness / o.rows;
  const bool fracture = o.fracture == "on";
  const auto load = fracture ? floating_ice::break_load(scene) : floating_ice::deflection_load(scene);
  auto settings = floating_ice::water_settings(scene, l0, 30);
  if (fracture) settings.profile_at = load.unloaded + load.ramp + load.hold;
  if (o.end_time > 0) settings.t_end = o.end_time;
  settings.out = o.no_output ? std::string() : o.out;
  std::printf("water: %g m deep under the ice, %g m of open water; damping %.3f/s; ice inertia x%g; end load: %g s "
              "without, a half cosine over %g s to %.2f N/m%s; to %g s at most\n",
              scene.beam_bottom(l0), scene.tank_length(l0) - scene.beam_length_for(l0), settings.damping,
              settings.inertia_scale, load.unloaded, load.ramp, load.ramped,
              fracture ? ", held 2 s, then rising by 0.02 P_f per second until the beam breaks" : ", held",
              settings.t_end);
  const auto r = o.dim == 3 ? run_in_water_as<3>(scene, settings, load, fracture)
                            : run_in_water_as<2>(scene, settings, load, fracture);
  Outcome c;
  if (r.blew_up) c.error = r.error + " (the files written until then stay)";
  const auto& d = r.at_profile;
  c.deflection.load = d.load;
  c.deflection.end_error = d.from_start.end;
  c.deflection.profile_rms = d.from_start.rms;
  c.deflection.balance_error = r.largest_balance_error;
  c.deflection.x = d.x;
  c.deflection.w = d.w;
  c.deflection.moment_error = d.moment_error;
  c.moment_before_load = r.moment_at_start;
  c.roll = r.roll;
  c.sideways = r.sideways;
  c.brk = r.broken;
  c.end_time = r.end_time;
  c.wall_seconds = r.wall_seconds;
  c.fluid_solves_per_step = r.fluid_solves_per_step;
  c.fluid_seconds = r.fluid_seconds;
  c.solid_seconds = r.solid_seconds;
  c.most_fluid_solves = r.most_fluid_solves;
  c.particles = r.ice_particles + r.water_particles;
  c.water_particles = r.water_particles;
  c.steps = r.steps;
  return c;
}

}  // namespace

int main(int argc, char** argv) try {
  Options o;
  mpsfsi_examples::CaseOptions cli(
      "floating_ice_beam", "Floating ice under an end load, on its water or on springs, against Hetenyi's beam");
  cli.add("--foundation", o.foundation, "water: the ice floats on simulated water; springs: a Winkler foundation")
      ->check(mpsfsi_examples::one_of({"water", "springs"}));
  cli.add("--thickness", o.thickness, "ice thickness h; 0: 0.08 with water, 0.04 on springs", "m");
  cli.add("--ice-density", o.ice_density, "ice density; 0: 875 with water (its draft whole rows at 8 rows), 917 on springs",
          "kg/m3");
  cli.add("--rows", o.rows, "particles through the thickness (h / l0), at least 2");
  cli.add("--dim", o.dim, "2, or 3 for a strip across a channel")->check(mpsfsi_examples::one_of({"2", "3"}));
  cli.add("--width", o.width, "with --dim 3: the strip's width, rounded to whole spacings; 0: 3 h", "m");
  cli.add("--fracture", o.fracture, "raise the load past P_f until the beam breaks")
      ->check(mpsfsi_examples::one_of({"on", "off"}));
  cli.add("--end-time", o.end_time, "with water: stop at this simulated time; 0: the protocol's end", "s");
  cli.add("--after-failure", o.after_failure,
          "on springs: how long the load goes on rising after the first failure, for the default ice (the "
          "protocol's times scale with sqrt(rho_i h))", "s");
  cli.add("--out", o.out, "output folder");
  cli.flag("--no-output", o.no_output, "write no files");
  if (const auto code = cli.parse_or_exit_code(argc, argv)) return *code;
  const bool water = o.foundation == "water";
  if (o.thickness == 0) o.thickness = water ? 0.08 : 0.04;
  auto usage_error = [](const char* message, double value) {
    std::fprintf(stderr, "floating_ice_beam: %s, not %g (see floating_ice_beam --help)\n", message, value);
    return 2;
  };
  if (o.thickness < 0) return usage_error("--thickness: must be positive, or 0 for the foundation's own", o.thickness);
  if (o.ice_density < 0) return usage_error("--ice-density: must be positive, or 0 for the foundation's own", o.ice_density);
  if (const double water_density = mpsfsi::scenes::FloatingIceBeam{}.water_density;
      water && o.ice_density >= water_density) {
    std::fprintf(stderr, "floating_ice_beam: --ice-density: must be below the water's %g kg/m3 for the ice to float, "
                 "not %g (see floating_ice_beam --help)\n", water_density, o.ice_density);
    return 2;
  }
  if (o.rows < 2) return usage_error("--rows: must be at least 2", o.rows);
  if (o.end_time < 0) return usage_error("--end-time: must be positive, or 0 for the protocol's end", o.end_time);
  if (o.end_time > 0 && !water) return usage_error("--end-time: only with --foundation water", o.end_time);
  if (o.width < 0) return usage_error("--width: must be positive, or 0 for 3 h", o.width);
  if (!(o.after_failure > 0)) return usage_error("--after-failure: must be positive", o.after_failure);
  if (o.after_failure != 0.1 && water)
    return usage_error("--after-failure: only with --foundation springs", o.after_failure);
  if (o.width > 0 && o.dim != 3) return usage_error("--width: only with --dim 3", o.width);
  if (cli.print_case_if_requested()) return 0;
  mpsfsi::scenes::FloatingIceBeam scene = water ? floating_ice::water_scene() : mpsfsi::scenes::FloatingIceBeam{};
  scene.thickness = o.thickness;
  if (o.ice_density > 0) scene.ice_density = o.ice_density;
  if (o.dim == 3) scene.width = o.width > 0 ? o.width : 3 * o.thickness;
  if (!o.no_output) {
    mpsfsi_examples::make_output_folder(o.out);
    cli.write_case(o.out);
  }
  const double l0 = o.thickness / o.rows;
  std::printf("Floating ice %s %s: h = %g m, l0 = %g m (%d rows), beam %g m, %g kg/m3, E = %g MPa, sigma_f = %g "
              "kPa",
              o.dim == 3 ? "strip (3D)" : "beam", water ? "in water" : "on a Winkler foundation", scene.thickness, l0,
              o.rows, scene.beam_length_for(l0), scene.ice_density, scene.youngs_modulus / 1e6,
              scene.tensile_strength / 1e3);
  if (o.dim == 3) std::printf(", width %g m (loads per unit width)", scene.width_for(l0));
  std::printf("\n");
  std::printf("Hetenyi: 1/lambda = %.4f m, pi/(4 lambda) = %.4f m, P_f = %.3f N/m\n", 1 / scene.lambda(),
              scene.largest_moment_position(), scene.failure_load());
  const auto r = water ? run_in_water(scene, o) : run_on_springs(scene, o);
  const bool fracture = o.fracture == "on";
  if (!r.error.empty()) {
    std::fprintf(stderr, "floating_ice_beam: %s\n", r.error.c_str());
    return 1;
  }

  const auto& d = r.deflection;
  if (d.load > 0)
    std::printf("deflection at P = %.3f N/m (%.2f P_f): end %.4e m, %+.2f %% from Hetenyi's; profile RMS to 3/lambda "
                "%.2f %% of it; %s %+.1e\n",
                d.load, d.load / scene.failure_load(), d.w[0], 100 * d.end_error, 100 * d.profile_rms,
                water ? "largest |F/(W+P) - 1| of a 1 s mean after the ramp" : "foundation force / P - 1",
                d.balance_error);
  if (d.load > 0) {
    std::printf("moment at pi/(4 lambda): %+.2f %% from Hetenyi's", 100 * d.moment_error);
    if (water)
      std::printf("; before the load %+.2f %% of the breaking moment (+: in the load's sense)",
                  -100 * r.moment_before_load / (scene.tensile_strength * scene.thickness * scene.thickness / 6));
    std::printf("\n");
  }
  const double x_f = scene.largest_moment_position(), Pf = scene.failure_load();
  const auto& b = r.brk;
  if (fracture) {
    if (b.failures == 0) {
      std::printf("break: no failure by t = %g s\n", r.end_time);
    } else {
      const bool top = scene.beam_bottom(l0) + scene.thickness - b.first_failure[1] < l0;
      std::printf("break: first failure at t = %.4f s, x = %.4f m (%+.1f %% from pi/(4 lambda)), %s fibre, P = %.3f N/m "
                  "(%+.1f %% of P_f); %zu failures, %zu bonds cut; %zu pieces of more than 10 particles, %zu particles "
                  "in smaller ones, %zu outside the two largest\n",
                  b.first_failure_time, b.first_failure[0], 100 * (b.first_failure[0] / x_f - 1), top ? "top" : "inner",
                  -b.load_at_failure[1], 100 * (-b.load_at_failure[1] / Pf - 1), b.failures, b.cut_bonds, b.pieces,
                  b.small_fragment_particles, b.beside_two_largest);
      if (b.pieces >= 2)
        std::printf("break: the far piece from x = %.4f m (%+.1f %% from pi/(4 lambda))\n", b.far_piece_start,
                    100 * (b.far_piece_start / x_f - 1));
    }
  }
  if (water && o.dim == 3)
    std::printf("strip: at the end rolled by %.2e m (side at z = width less side at z = 0, down), moved across the "
                "channel by %.2e m\n", r.roll, r.sideways);
  if (water) {
    const double solves = std::max(1.0, r.fluid_solves_per_step * static_cast<double>(r.steps));
    std::printf("time: water %.1f s (%.1f ms a fluid solve), ice %.1f s, coupling and output %.1f s\n", r.fluid_seconds,
                1e3 * r.fluid_seconds / solves, r.solid_seconds, r.wall_seconds - r.fluid_seconds - r.solid_seconds);
  }
  std::printf("summary: end deflection %+.2f %%, profile RMS %.2f %%, moment %+.2f %%, balance %+.1e",
              100 * d.end_error, 100 * d.profile_rms, 100 * d.moment_error, d.balance_error);
  if (water)
    std::printf(", fluid solves per step %.2f (at most %d)", r.fluid_solves_per_step, r.most_fluid_solves);
  if (b.failures > 0)
    std::printf(", first failure x %+.1f %%, P %+.1f %%, pieces %zu", 100 * (b.first_failure[0] / x_f - 1),
                100 * (-b.load_at_failure[1] / Pf - 1), b.pieces);
  if (b.pieces >= 2) std::printf(", break x %+.1f %%", 100 * (b.far_piece_start / x_f - 1));
  std::printf("; %zu particles", r.particles);
  if (water) std::printf(" (%zu of water and tank)", r.water_particles);
  std::printf(", %lld steps, %.1f s on %d threads\n", r.steps, r.wall_seconds, mpsfsi::parallel::max_threads());
  if (!o.no_output) {
    mpsfsi::CsvWriter summary(o.out + "/summary.csv",
                              {"water", "thickness", "l0", "beam_length", "lambda", "failure_load", "largest_moment_x",
                               "profile_load", "end_error", "profile_rms", "moment_error", "moment_before_load",
                               "balance_error", "failures",
                               "first_failure_x", "first_failure_y", "load_at_failure", "pieces", "far_piece_x",
                               "fluid_solves_per_step", "wall_s"});
    summary.row({water ? 1.0 : 0.0, scene.thickness, l0, scene.beam_length_for(l0), scene.lambda(), Pf, x_f, d.load,
                 d.end_error, d.profile_rms, d.moment_error, r.moment_before_load, d.balance_error,
                 static_cast<double>(b.failures), b.first_failure[0],
                 b.first_failure[1], -b.load_at_failure[1], static_cast<double>(b.pieces), b.far_piece_start,
                 r.fluid_solves_per_step, r.wall_seconds});
    std::printf("wrote %s (case.yaml reruns this case); plot with python3 examples/floating_ice_beam/plot.py %s\n",
                o.out.c_str(), o.out.c_str());
  }
  return 0;
} catch (const mpsfsi::SimulationError& e) {
  std::fprintf(stderr, "floating_ice_beam: %s\n", e.what());
  return 1;
} catch (const mpsfsi::Error& e) {
  std::fprintf(stderr, "floating_ice_beam: %s\n", e.what());
  return 1;
}
