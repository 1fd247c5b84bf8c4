// SPDX-License-Identifier: BSD-3-Clause
// Floating ice coupled to its water: the ice of scenes::FloatingIceBeam floats on the water of its
// tank, both under gravity, and its end is loaded (docs/validation/fsi.md, "Floating ice beam under
// an end load"). Deflection against Hetenyi's semi-infinite beam on the Winkler foundation
// k = rho_w g, the break against his largest moment. The 2D beam, or in 3D the scene's strip
// across its channel. Used by the floating_ice_beam example (--foundation water) and by
// tests/verification/floating_beam_in_water.cpp and fsi.cpp.
#pragma once

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstddef>
#include <cstdio>
#include <memory>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include <mpsfsi/fluid/fluid_solver.hpp>
#include <mpsfsi/fluid/water_under_structure.hpp>
#include <mpsfsi/fsi/fsi_coupler.hpp>
#include <mpsfsi/io/csv_writer.hpp>
#include <mpsfsi/io/pvd_writer.hpp>
#include <mpsfsi/io/vtu_writer.hpp>
#include <mpsfsi/scenes/floating_ice_beam.hpp>
#include <mpsfsi/solid/elastic_solver.hpp>

#include "common/output_folder.hpp"
#include "floating_ice_beam/beam_on_foundation.hpp"

namespace floating_ice {

// The water under the ice: the settings for water under a long structure (docs/theory.md, section
// 2.9), with negative pressures kept; gravity along -y, the scene's vertical in 2D and 3D. In 3D
// the PPE is solved by the SSOR-CG deflated by aggregates: on the strip's water it needs about 13
// iterations instead of 76 and takes less than half the time (docs/performance.md, coupled steps).
// The 2D runs keep the plain SSOR-CG with which their figures were taken.
template <int Dim = 2>
struct UnderIceWater : WaterUnderLongStructure<Dim> {};
template <>
struct UnderIceWater<3> : WaterUnderLongStructure<3> {
  using linear_solver = DeflatedSsorCg;
};

template <int Dim = 2>
FluidParameters<Dim> water_under_ice_parameters(double l0, double dt) {
  FluidParameters<Dim> fp;
  fp.l0 = l0;
  fp.dt = dt;
  fp.negative_pressure = NegativePressure::keep;
  const double g = fp.gravity.norm();
  fp.gravity = Vec<Dim>::Zero();
  fp.gravity[1] = -g;
  return under_structure(fp);
}

// The floating beam's ice: scenes::FloatingIceBeam's material (in plane stress in 2D), its inertia scaled by
// `inertia_scale` and its gravity by the inverse (the weight stays), with the brittle solid's bond
// viscosity (solid_parameters.hpp): without it the scaled ice's own vibrations, a few coupling steps
// long at large inertias, grow under the lagging load as well.
template <int Dim = 2>
SolidParameters<Dim> floating_ice_parameters(const scenes::FloatingIceBeam& scene, double l0, double inertia_scale) {
  SolidParameters<Dim> sp;
  sp.l0 = l0;
  sp.density = scene.ice_density * inertia_scale;
  sp.gravity = Vec<Dim>::Zero();
  sp.gravity[1] = -scene.gravity / inertia_scale;
  sp.youngs_modulus = scene.youngs_modulus;
  sp.poisson_ratio = scene.poisson_ratio;
  sp.plane_model = PlaneModel::plane_stress;
  sp.bond_viscosity = SolidParameters<2>::fracture_bond_viscosity;
  return sp;
}

// The end load's history, N per unit width, downwards: none for `unloaded` seconds, then a half
// cosine over `ramp` up to `ramped`, held for `hold`, then rising by `rate` per second.
struct EndLoad {
  double unloaded = 4, ramp = 10, ramped = 0, hold = 0, rate = 0;
  double at(double t) const {
    const double s = (t - unloaded) / ramp;
    if (s <= 0) return 0;
    if (s < 1) return ramped * 0.5 * (1 - std::cos(std::acos(-1.0) * s));
    return ramped + rate * std::max(0.0, t - unloaded - ramp - hold);
  }
};

// The run's settings: the ice's inertia scaled by `inertia_scale` (floating_ice_parameters), the
// water's kinematic viscosity (docs/validation/fluid.md, water under a structure), and the damping
// rate `damping` (1/s) of the water's and the ice's motion: each water particle's velocity scaled
// by exp(-damping dt) after each step, the ice given the same mass-proportional damping
// (SolidParameters::damping); damping forces vanish at rest. The step is the fluid's automatic one
// (its Courant and viscous limits, FluidParameters) capped at `max_dt`. The profile against
// Hetenyi's is taken at `profile_at` (s; by default at the end). A run with fracture stops
// `after_failure` seconds after the first failure. With `out` set the run writes its files there
// (deflection.csv, history.csv, failures.csv, ice.pvd and water.pvd with their VTU snapshots every
// `snapshot_every` seconds, every `snapshot_every / 25` during `after_failure`).
struct WaterRunSettings {
  double l0 = 0.01;
  double max_dt = 5e-3;
  double inertia_scale = 16;
  double kinematic_viscosity = 1e-3;
  double damping = 0;
  double t_end = 30;
  double profile_at = -1;
  double after_failure = 0.5;
  std::string out;
  double snapshot_every = 0.5;
};

// Deflections against Hetenyi's under the present load P. `from_start`: each column measured from
// the beam's shape when the load began, against Hetenyi's less the open water's rise
// (FloatingIceBeam::level_rise). `from_far_end`: measured from where each column started, less the
// far end's column, against Hetenyi's. Both are relative errors at the end column and RMS over
// 0 <= x <= 3 / lambda relative to Hetenyi's end deflection (FloatingIceBeam::profile_error).
// `moment`: the bending moment at pi / (4 lambda) (FloatingIceBeam::column_moment), the whole of
// it, the unloaded beam's included, as the failure check reads it.
struct Deflections {
  double load = 0;  // P, N/m
  scenes::FloatingIceBeam::ProfileError from_start, from_far_end;
  double end = 0;              // m, the end column from the load's start
  std::vector<double> x, w;    // column centres and the deflections from the load's start plus the rise
  double moment = 0;           // N m/m
  double moment_error = 0;     // moment / Hetenyi's - 1
};

struct WaterRunResult {
  Deflections at_profile;            // at profile_at
  Deflections at_end;                // at the run's end (t_end, or after the first failure's run-on)
  double moment_at_start = 0;        // N m/m at pi / (4 lambda) when the load starts
  // Largest |F / (W + P) - 1| of the 1 s means, from 1 s after the ramp to the first failure.
  double largest_balance_error = 0;
  double run_balance_error = 0;      // the same over the whole run
  int water_on_ice = 0;              // water particles above the ice's top face at the end
  double sinking = 0;                // the ice's mean displacement downwards at the end, m
  // 3D: at the end, the mean displacement downwards of the strip's side at z = width less that of
  // its side at z = 0 (a roll about the strip's long axis), and the strip's mean displacement
  // across the channel, m. The scene is mirror symmetric about the channel's mid-plane.
  double roll = 0, sideways = 0;
  double fluid_solves_per_step = 0;
  int most_fluid_solves = 0;
  long long steps = 0;
  double end_time = 0;
  std::size_t ice_particles = 0, water_particles = 0;
  BreakResult broken;  // with a failure model: where and when the ice first failed, the pieces
  double wall_seconds = 0;
  double fluid_seconds = 0, solid_seconds = 0;  // of wall_seconds: the water's steps, the ice's advances
  bool blew_up = false;
  std::string error;  // the blow-up's message: step, time and particle
};

// The ice's mean sinking and, in 3D, its roll and drift across the channel (WaterRunResult), from
// its positions x and reference positions x0.
template <int Dim>
void set_ice_motion(const VecArray<Dim, double>& x, const VecArray<Dim, double>& x0, double l0, double width,
                    WaterRunResult& r) {
  const auto n = static_cast<double>(x.size());
  double side_low = 0, side_high = 0;
  int n_low = 0, n_high = 0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    const double down = x0[i][1] - x[i][1];
    r.sinking += down / n;
    if constexpr (Dim == 3) {
      r.sideways += (x[i][2] - x0[i][2]) / n;
      if (x0[i][2] < l0) {
        side_low += down;
        ++n_low;
      } else if (x0[i][2] > width - l0) {
        side_high += down;
        ++n_high;
      }
    }
  }
  if (n_low > 0 && n_high > 0) r.roll = side_high / n_high - side_low / n_low;
}

// Runs the beam (h and the ice's material from `scene`) under `load`, IQN-ILS without eq 10's
// interface acceleration and with the linear fit of eq 18's pressure (docs/theory.md, 4.3-4.4).
// The loaded end is on a roller at mid-thickness against the tank wall (roller_particles); its
// column carries P, spread evenly over its particles. The wetted bottom face is marked as under a
// distributed load, the water's, for the failure read-out. `Ice` is the solid: ElasticSolver<Dim>
// (nothing fails) or IceSolverOf<Dim> (brittle). In 3D the ice is the scene's strip across its
// channel: the roller is the end column's mid-thickness row, the end load P times the width is
// shared by the end column's particles, and forces are reported per unit width. Prints the state
// every simulated second. A blow-up ends the run with `blew_up` set and its message printed; the
// files written until then stay.
template <class Ice>
WaterRunResult run_in_water(const scenes::FloatingIceBeam& scene, const WaterRunSettings& s, const EndLoad& load) {
  constexpr int Dim = Ice::dimension;
  const double l0 = s.l0;
  std::vector<std::size_t> end_column;
  auto sp = floating_ice_parameters<Dim>(scene, l0, s.inertia_scale);
  sp.damping = s.damping;
  sp.tensile_strength = scene.tensile_strength;
  auto beam = scene.beam_particles<Dim>(l0, end_column);
  const auto roller = scene.roller_particles(beam, end_column, l0);
  Ice ice(std::move(beam), sp);
  for (const auto i : roller) ice.support(i, Vec<Dim>::UnitX());
  for (const auto i : scene.wetted_bottom(ice.reference_positions(), l0)) ice.mark_distributed_load(i);
  auto fp = water_under_ice_parameters<Dim>(l0, 0);
  fp.max_dt = s.max_dt;
  fp.kinematic_viscosity = s.kinematic_viscosity;
  CouplingParameters cp;
  cp.interface_acceleration = false;
  cp.interface_pressure = InterfacePressure::linear_fit;
  FsiCoupler<FluidSolver<Dim, UnderIceWater<Dim>>, Ice, InterfaceQuasiNewton> coupler(
      scene.fluid_particles<Dim>(l0), fp, std::move(ice), cp);
  const auto& solid = coupler.solid();
  const double width = Dim == 3 ? scene.width_for(l0) : 1.0;  // loads and forces per unit width
  const double weight = scene.ice_density * scene.gravity * scene.thickness * scene.beam_length_for(l0);
  const double top_row = scene.beam_bottom(l0) + scene.thickness - 0.5 * l0;
  auto lift = [&] { return coupler.total_interface_force()[1] / width; };  // the water's force on the ice, N/m
  VecArray<Dim, double> start_shape = solid.reference_positions();
  WaterRunResult r;
  r.ice_particles = solid.particles().size();
  r.water_particles = coupler.structure_offset();

  const double x_f = scene.largest_moment_position();
  auto moment = [&] { return scene.column_moment(coupler.solid().stresses(), solid.reference_positions(), x_f, l0); };
  auto deflections = [&](double P) {
    Deflections d;
    d.load = P;
    d.moment = moment();
    d.moment_error = d.moment / scene.moment(P, x_f) - 1;
    d.w = scene.column_deflections(solid.particles().positions(), start_shape, l0);
    d.end = d.w[0];
    for (std::size_t c = 0; c < d.w.size(); ++c) {
      d.w[c] += scene.level_rise(P, l0);
      d.x.push_back((static_cast<double>(c) + 0.5) * l0);
    }
    d.from_start = scene.profile_error(d.w, P, l0);
    auto w = scene.column_deflections(solid.particles().positions(), solid.reference_positions(), l0);
    const double far_end = w.back();
    for (auto& wc : w) wc -= far_end;
    d.from_far_end = scene.profile_error(w, P, l0);
    return d;
  };
  auto water_on_ice = [&] {
    const auto w = scene.column_deflections(solid.particles().positions(), solid.reference_positions(), l0);
    const auto& fluid = coupler.fluid().particles();
    int n = 0;
    for (std::size_t i = 0; i < fluid.size(); ++i) {
      const auto& x = fluid.positions()[i];
      const auto c = static_cast<std::size_t>(std::max(0.0, x[0] / l0));
      if (fluid.kinds()[i] == ParticleKind::fluid && x[0] > 0 && c < w.size() && x[1] > top_row - w[c]) ++n;
    }
    return n;
  };

  // Files: the history every 0.05 s, VTU snapshots of the ice and the water.
  std::unique_ptr<PvdWriter> ice_pvd, water_pvd;
  std::unique_ptr<CsvWriter> history;
  std::size_t frames = 0;
  double next_snapshot = 0, next_sample = 0;
  if (!s.out.empty()) {
    mpsfsi_examples::make_output_folder(s.out);
    ice_pvd = std::make_unique<PvdWriter>(s.out + "/ice.pvd");
    water_pvd = std::make_unique<PvdWriter>(s.out + "/water.pvd");
    history = std::make_unique<CsvWriter>(
        s.out + "/history.csv",
        std::vector<std::string>{"t", "P", "end_deflection", "hetenyi_end_deflection", "foundation_force",
                                 "failures", "cut_bonds", "fluid_solves"});
  }
  auto snapshot = [&] {
    if (!ice_pvd) return;
    const std::string ice_file = numbered_file_name("ice", frames), water_file = numbered_file_name("water", frames);
    ++frames;
    write_vtu(s.out + "/" + ice_file, coupler.solid().output());
    write_vtu(s.out + "/" + water_file, coupler.fluid().particles());
    ice_pvd->add(coupler.time(), ice_file);
    water_pvd->add(coupler.time(), water_file);
  };
  auto write_profile = [&](const Deflections& d) {
    if (s.out.empty()) return;
    CsvWriter profile(s.out + "/deflection.csv", {"x", "w", "hetenyi_w"});
    for (std::size_t c = 0; c < d.w.size(); ++c) profile.row({d.x[c], d.w[c], scene.deflection(d.load, d.x[c])});
  };

  long long solves = 0;
  double second_sum = 0, second_time = 0, next_report = 1, dt = s.max_dt;
  const double held_from = load.unloaded + load.ramp;
  const double profile_at = s.profile_at >= 0 ? s.profile_at : s.t_end;
  bool shape_taken = load.unloaded <= 0, failure_reported = false, profile_taken = false;
  double stop_at = s.t_end;
  const auto wall_start = std::chrono::steady_clock::now();
  snapshot();
  next_snapshot = s.snapshot_every;
  try {
    // Half a step's margin: the summed steps miss a whole second by round-off.
    while (coupler.time() < stop_at - 0.5 * dt) {
      const double P = load.at(coupler.time() + dt);
      auto& applied = coupler.applied_force();
      for (const auto i : end_column) applied[i][1] = -P * width / static_cast<double>(end_column.size());
      const double t_before = coupler.time();
      coupler.step();
      dt = coupler.time() - t_before;
      ++r.steps;
      solves += coupler.last_iterations();
      r.most_fluid_solves = std::max(r.most_fluid_solves, coupler.last_iterations());
      auto& fluid = coupler.fluid().particles();
      const double velocity_factor = std::exp(-s.damping * dt);
      for (std::size_t i = 0; i < fluid.size(); ++i)
        if (fluid.kinds()[i] == ParticleKind::fluid) fluid.velocities()[i] *= velocity_factor;
      const double t = coupler.time();
      if (!shape_taken && t >= load.unloaded - 1e-12) {
        start_shape = solid.particles().positions();
        r.moment_at_start = moment();
        shape_taken = true;
      }
      const bool failed = solid.first_failure_time() >= 0;
      if (failed && !failure_reported) {
        failure_reported = true;
        stop_at = std::min(s.t_end, solid.first_failure_time() + s.after_failure);
        const auto& first = solid.reference_positions()[solid.failure_log().front().particle];
        std::printf("  first failure at t %.3f s, P %.2f N/m, at x %.3f m, y %.4f m (reference)\n",
                    solid.first_failure_time(), load.at(solid.first_failure_time()), first[0], first[1]);
      }
      if (!profile_taken && P > 0 && t >= profile_at - 0.5 * dt) {
        profile_taken = true;
        r.at_profile = deflections(P);
        write_profile(r.at_profile);
      }
      if (history && t >= next_sample - 0.5 * dt) {
        next_sample += 0.05;
        const auto w = scene.column_deflections(solid.particles().positions(), start_shape, l0);
        history->row({t, P, w[0], scene.deflection(P, 0.5 * l0) - scene.level_rise(P, l0),
                      lift() - weight, static_cast<double>(solid.failure_events()),
                      static_cast<double>(solid.cut_bonds()), static_cast<double>(coupler.last_iterations())});
      }
      const bool fracturing = failed && t < solid.first_failure_time() + s.after_failure;
      const double fracture_every = s.snapshot_every / 25;
      if (t >= next_snapshot - 0.5 * dt || (fracturing && next_snapshot > t + fracture_every)) {
        snapshot();
        next_snapshot = t + (fracturing ? fracture_every : s.snapshot_every);
      }
      second_sum += (lift() / (weight + P) - 1) * dt;
      second_time += dt;
      if (t < next_report - 0.5 * dt && t < stop_at - 0.5 * dt) continue;
      next_report += 1;
      const double balance = second_sum / second_time;
      second_sum = 0;
      second_time = 0;
      if (!failed) {
        r.run_balance_error = std::max(r.run_balance_error, std::abs(balance));
        if (t > held_from + 1 - 1e-9) r.largest_balance_error = std::max(r.largest_balance_error, std::abs(balance));
      }
      const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
      std::printf("  t %5.2f s  P %6.2f N/m  F/(W+P) - 1 over 1 s %+.5f", t, P, balance);
      if (P > 0) {
        const auto d = deflections(P);
        std::printf("  end %6.3f mm (%+.1f %%), RMS %4.1f %%; from the far end %+.1f %%, RMS %4.1f %%; moment at "
                    "pi/(4 lambda) %+.1f %%", 1e3 * d.end, 100 * d.from_start.end, 100 * d.from_start.rms,
                    100 * d.from_far_end.end, 100 * d.from_far_end.rms, 100 * d.moment_error);
      }
      std::printf("  failures %zu  water on the ice %d  solves/step %.2f  step %.2f ms  wall %.0f s, %.0f s left\n",
                  solid.failure_events(), water_on_ice(), double(solves) / double(r.steps), 1e3 * dt, wall,
                  wall / t * (stop_at - t));
      std::fflush(stdout);
    }
  } catch (const SimulationError& e) {
    std::printf("  (floating beam in water: %s)\n", e.what());
    r.blew_up = true;
    r.error = e.what();
  }
  r.end_time = coupler.time();
  if (!r.blew_up) snapshot();
  const double P_end = load.at(coupler.time());
  if (P_end > 0) r.at_end = deflections(P_end);
  if (!profile_taken && P_end > 0 && !r.blew_up) {
    r.at_profile = r.at_end;
    write_profile(r.at_profile);
  }
  r.water_on_ice = water_on_ice();
  set_ice_motion(solid.particles().positions(), solid.reference_positions(), l0, width, r);
  r.fluid_solves_per_step = r.steps > 0 ? double(solves) / double(r.steps) : 0;
  r.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
  r.fluid_seconds = coupler.fluid_seconds();
  r.solid_seconds = coupler.solid_seconds();
  if constexpr (std::is_same_v<Ice, IceSolverOf<Dim>>) {
    r.broken = read_break(solid, wall_start);
    if (r.broken.failures > 0) {
      r.broken.load_at_failure = Vec<2>(0, -load.at(r.broken.first_failure_time));
      if (!s.out.empty()) write_failures(s.out, solid);
    }
  }
  return r;
}

// The verified scene: h = 80 mm at l0 = 10 mm (8 particles through the thickness), 5.06 m of ice
// (5 / lambda) on 0.25 m of water with 0.3 m of open water; E = 60 MPa, nu = 0.3, sigma_f = 30 kPa:
// 1 / lambda = 1.01 m, pi / (4 lambda) = 0.79 m, P_f = 98.2 N/m. The ice is 875 kg/m3, within the
// densities measured for first-year sea ice above the waterline (840-910 kg/m3; Timco & Frederking
// 1996, Cold Reg. Sci. Technol. 24), which makes the draft exactly 7 of the 8 rows: the open
// water's level then holds the unloaded beam in equilibrium.
inline scenes::FloatingIceBeam water_scene() {
  scenes::FloatingIceBeam scene;
  scene.thickness = 0.08;
  scene.ice_density = 875;
  return scene;
}

// The settings at spacing l0 to t_end. The damping is critical for the slowest motion, the water's
// quarter-wave sloshing under the beam from the loaded end's wall to the open water:
// omega = (pi / 2) sqrt(g H) / L with H the depth under the beam and L the tank (0.46/s, a 14 s
// period, in the verified scene), damping 2 omega.
inline WaterRunSettings water_settings(const scenes::FloatingIceBeam& scene, double l0, double t_end) {
  WaterRunSettings s;
  s.l0 = l0;
  const double depth = scene.beam_bottom(l0), tank = scene.tank_length(l0);
  s.damping = std::acos(-1.0) * std::sqrt(scene.gravity * depth) / tank;
  s.t_end = t_end;
  return s;
}

// The two protocols (docs/validation/fsi.md). Deflection: P_f / 2 after 4 s without load, as a
// half cosine over 10 s, held to 30 s. Break: after 2 s without load, a half cosine over 10 s to
// 0.9 P_f, held for 2 s, then rising by 0.02 P_f per second.
inline EndLoad deflection_load(const scenes::FloatingIceBeam& scene) {
  EndLoad load;
  load.ramped = scene.failure_load() / 2;
  return load;
}
inline EndLoad break_load(const scenes::FloatingIceBeam& scene) {
  EndLoad load;
  load.unloaded = 2;
  load.ramped = 0.9 * scene.failure_load();
  load.hold = 2;
  load.rate = 0.02 * scene.failure_load();
  return load;
}

}  // namespace floating_ice
