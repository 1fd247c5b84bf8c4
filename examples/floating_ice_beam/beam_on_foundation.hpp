// SPDX-License-Identifier: BSD-3-Clause
// Floating ice as a beam on the water's Winkler foundation k = rho_w g: the ice of
// scenes::FloatingIceBeam on springs under its bottom row, loaded at its end, against Hetenyi's
// semi-infinite beam (docs/validation/fracture.md, "Ice on an elastic foundation"). 2D, or in 3D a
// strip across the scene's width (scenes::FloatingIceBeam::width) under a line load along its end.
// Used by the floating_ice_beam example and by tests/verification/ice_on_foundation.cpp.
#pragma once

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstddef>
#include <limits>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include <mpsfsi/fracture/fracture_process.hpp>
#include <mpsfsi/io/csv_writer.hpp>
#include <mpsfsi/io/progress.hpp>
#include <mpsfsi/io/pvd_writer.hpp>
#include <mpsfsi/io/vtu_writer.hpp>
#include <mpsfsi/scenes/floating_ice_beam.hpp>
#include <mpsfsi/solid/elastic_solver.hpp>
#include <mpsfsi/solid/fragments.hpp>

#include "common/output_folder.hpp"

namespace floating_ice {

using namespace mpsfsi;
template <int Dim>
using IceSolverOf = ElasticSolver<Dim, BrittleSolidPolicies<Dim>>;
using IceSolver = IceSolverOf<2>;

// The lowest frequency of a beam on a Winkler foundation, sqrt(k / (rho_i h)) (1/s): the cut-off
// of its flexural waves.
inline double omega0(const scenes::FloatingIceBeam& scene) {
  return std::sqrt(scene.foundation_modulus() / (scene.ice_density * scene.thickness));
}

// The ice beam of the scene, its bottom row on springs k l0^(Dim-1) (the foundation k = rho_w g over
// a particle's share of the bottom face: l0, or l0 x l0 in 3D), its end column loaded by P(t)
// downwards (in 3D P times the strip's width, shared by the end column's particles), no gravity (weight
// and buoyancy cancel at the draft; the springs carry the change of buoyancy). Mass damping at
// the lowest frequency of a beam on a Winkler foundation, omega_0 = sqrt(k / (rho_i h)) (the
// cut-off of its flexural waves), critically damps that mode and makes every other one decay at
// omega_0 (mass damping c gives each underdamped mode the decay rate c / 2): the beam settles
// within a few 1 / omega_0 of any change of load (61 ms at h = 40 mm).
template <int Dim = 2>
class BeamOnFoundation {
 public:
  using solver_type = IceSolverOf<Dim>;

  // With `hydrostatic_limits` a spring's force stays between the column's weight downwards (its
  // bottom out of the water: lifted by more than the draft) and the buoyancy of its whole
  // thickness minus the weight (its top under water): Archimedes for an upright column.
  BeamOnFoundation(const scenes::FloatingIceBeam& scene, double l0, bool can_fail, bool hydrostatic_limits = false)
      : scene_(scene), l0_(l0), solver_(make_solver(scene, l0, can_fail)), limits_(hydrostatic_limits) {
    const auto& x = solver_.reference_positions();
    const double yb = scene.beam_bottom(l0);
    for (std::size_t i = 0; i < x.size(); ++i) {
      if (x[i][1] < yb + l0) bottom_.push_back(i);
      if (x[i][0] < l0) end_.push_back(i);
    }
    if constexpr (Dim == 3) width_ = scene.width_for(l0);
    // The springs are a distributed traction on the bottom face, which the failure check reads on
    // the surface; the end column carries the end load, a concentrated one.
    for (const auto i : scene.wetted_bottom(x, l0)) solver_.mark_distributed_load(i);
  }

  // Steps to time t with the end load P(time) (N per unit width, downwards).
  template <class Load>
  void run_to(double t, Load load) {
    while (solver_.time() < t - 1e-12) {
      apply(load(solver_.time()));
      solver_.step();
    }
  }

  // Deflection (m, downwards) of each column, the mean over its particles, at the column's x.
  std::vector<double> deflection() const {
    return scene_.column_deflections(solver_.particles().positions(), solver_.reference_positions(), l0_);
  }
  double column_x(std::size_t c) const { return (static_cast<double>(c) + 0.5) * l0_; }

  // The foundation's force on the beam (N per unit width, upwards).
  double foundation_force() const {
    double f = 0;
    for (const auto i : bottom_) f += spring(i);
    return f / width_;
  }

  solver_type& solver() { return solver_; }
  const solver_type& solver() const { return solver_; }
  double l0() const { return l0_; }

 private:
  static solver_type make_solver(const scenes::FloatingIceBeam& scene, double l0, bool can_fail) {
    std::vector<std::size_t> end_column;
    auto set = scene.beam_particles<Dim>(l0, end_column);
    SolidParameters<Dim> p;
    p.l0 = l0;
    p.density = scene.ice_density;
    p.youngs_modulus = scene.youngs_modulus;
    p.poisson_ratio = scene.poisson_ratio;
    p.plane_model = scene.plane_strain ? PlaneModel::plane_strain : PlaneModel::plane_stress;
    p.tensile_strength = can_fail ? scene.tensile_strength : 1e30;  // out of reach: nothing fails
    p.damping = 2 * omega0(scene);
    return solver_type(std::move(set), p);
  }

  // Upward spring force of a bottom particle: k l0^(Dim-1) times its deflection.
  double spring(std::size_t i) const {
    double w = solver_.reference_positions()[i][1] - solver_.particles().positions()[i][1];
    if (limits_) w = std::clamp(w, -scene_.draft(), scene_.thickness - scene_.draft());
    return scene_.foundation_modulus() * std::pow(l0_, Dim - 1) * w;
  }

  void apply(double P) {
    auto& f = solver_.external_force();
    for (auto& fi : f) fi.setZero();
    for (const auto i : bottom_) f[i][1] += spring(i);
    for (const auto i : end_) f[i][1] -= P * width_ / static_cast<double>(end_.size());
  }

  scenes::FloatingIceBeam scene_;
  double l0_;
  solver_type solver_;
  std::vector<std::size_t> bottom_, end_;
  bool limits_ = false;
  double width_ = 1;  // the strip's width in 3D (loads are per unit width); 1 in 2D
};

// The settled deflection against Hetenyi's: the end column's error, the RMS over
// 0 <= x <= 3 / lambda relative to the end deflection, and the force balance.
struct DeflectionCheck {
  double load = 0;           // P (N/m)
  double end_error = 0;      // (w - w_ref) / w_ref at the end column
  double profile_rms = 0;    // RMS of w - w_ref over 0 <= x <= 3 / lambda, relative to w_ref at the end column
  double balance_error = 0;  // (foundation force - P) / P
  std::vector<double> x, w;  // the profile: column centres and deflections
  double moment_error = 0;   // the moment at pi / (4 lambda) (FloatingIceBeam::column_moment) / Hetenyi's - 1
};

template <int Dim>
DeflectionCheck check_deflection(BeamOnFoundation<Dim>& beam, const scenes::FloatingIceBeam& scene, double P) {
  DeflectionCheck r;
  r.load = P;
  r.w = beam.deflection();
  for (std::size_t c = 0; c < r.w.size(); ++c) r.x.push_back(beam.column_x(c));
  const auto error = scene.profile_error(r.w, P, beam.l0());
  r.end_error = error.end;
  r.profile_rms = error.rms;
  r.balance_error = beam.foundation_force() / P - 1;
  auto& solver = beam.solver();
  const double x_f = scene.largest_moment_position();
  r.moment_error = scene.column_moment(solver.stresses(), solver.reference_positions(), x_f, beam.l0()) /
                       scene.moment(P, x_f) - 1;
  return r;
}

// What a run to the first break leaves: the first failure, the load then and the pieces.
struct BreakResult {
  Vec<2> first_failure = Vec<2>::Zero();  // reference x and y of the first failed particle (in 3D, z left out)
  double first_failure_time = -1;
  Vec<2> load_at_failure = Vec<2>::Zero();  // the load on the ice then (N/m)
  std::size_t pieces = 0;                   // fragments of more than 10 particles
  std::size_t small_fragment_particles = 0;  // particles in fragments of 10 or fewer
  std::size_t beside_two_largest = 0;        // particles in neither of the two largest fragments
  double far_piece_start = 0;  // the smallest reference x of the largest piece (the far sheet)
  std::size_t failures = 0, cut_bonds = 0;
  std::size_t particles = 0;
  double wall_seconds = 0;
};

template <int Dim>
BreakResult read_break(const IceSolverOf<Dim>& s, std::chrono::steady_clock::time_point wall) {
  BreakResult r;
  r.particles = s.particles().size();
  r.failures = s.failure_events();
  r.cut_bonds = s.cut_bonds();
  r.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall).count();
  if (r.failures == 0) return r;
  r.first_failure = s.reference_positions()[s.failure_log().front().particle].template head<2>();
  r.first_failure_time = s.first_failure_time();
  const auto fragments = find_fragments(s.bonds());
  r.pieces = fragments.count_larger_than(10);
  const auto largest = static_cast<std::size_t>(
      std::max_element(fragments.sizes.begin(), fragments.sizes.end()) - fragments.sizes.begin());
  std::size_t second = 0;  // the size of the second largest fragment
  for (std::size_t f = 0; f < fragments.sizes.size(); ++f)
    if (f != largest) second = std::max(second, fragments.sizes[f]);
  r.beside_two_largest = r.particles - fragments.sizes[largest] - second;
  r.far_piece_start = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < fragments.label.size(); ++i) {
    const auto f = static_cast<std::size_t>(fragments.label[i]);
    if (fragments.sizes[f] <= 10) ++r.small_fragment_particles;
    if (f == largest) r.far_piece_start = std::min(r.far_piece_start, s.reference_positions()[i][0]);
  }
  return r;
}

// Every particle failure of `s`, with its reference position, as `folder/failures.csv` (z0 and
// normal_z in 3D).
template <int Dim>
void write_failures(const std::string& folder, const IceSolverOf<Dim>& s) {
  std::vector<std::string> columns{"t", "particle", "x0", "y0", "sigma_1", "normal_x", "normal_y"};
  if constexpr (Dim == 3) {
    columns.insert(columns.begin() + 4, "z0");
    columns.push_back("normal_z");
  }
  CsvWriter failures(folder + "/failures.csv", columns);
  for (const auto& e : s.failure_log()) {
    const Vec<Dim> X = s.reference_positions()[e.particle];
    if constexpr (Dim == 3)
      failures.row({e.time, static_cast<double>(e.particle), X[0], X[1], X[2], e.sigma1, e.normal[0], e.normal[1],
                    e.normal[2]});
    else
      failures.row({e.time, static_cast<double>(e.particle), X[0], X[1], e.sigma1, e.normal[0], e.normal[1]});
  }
}

// The example's run (floating_ice_beam): one beam, two phases.
//  1. Deflection: P ramps to P_f / 2 over 0.3 s (about 5 / omega_0 at h = 40 mm) and is held to
//     0.8 s, when the transient has decayed by e^(-omega_0 0.5 s) (1 + omega_0 0.5 s) = 2.5e-3;
//     the profile is compared with Hetenyi's.
//  2. Break (with fracture): P rises at the same rate to 0.9 P_f, is held for 0.3 s and then rises
//     by 0.2 P_f per second, so that the settling lag 2 / omega_0 = 0.12 s of the critically
//     damped mode costs 2.4 % of P_f; the run stops 0.1 s (RunOptions::after_failure) after the
//     first failure, or at 4 s.
// The times are for h = 40 mm; for another thickness they scale with 1 / omega_0.
struct RunOptions {
  int rows = 8;          // particles through the thickness, h / l0
  bool fracture = true;  // phase 2
  double after_failure = 0.1;  // how long phase 2 goes on after the first failure (s at h = 40 mm)
  std::string out;       // output folder; empty: no files
  bool progress = false;
};

struct RunResult {
  double l0 = 0, lambda = 0, failure_load = 0, omega0 = 0;
  std::size_t particles = 0;
  long long steps = 0;
  double end_time = 0;
  DeflectionCheck deflection;
  BreakResult brk;
  double wall_seconds = 0;
};

// The example's load P(t) (N/m, downwards) of the two phases above; `time_scale` is
// 1 / omega_0 over its value at h = 40 mm.
class ExampleLoad {
 public:
  ExampleLoad(double failure_load, double time_scale) : Pf_(failure_load), s_(time_scale) {}
  double operator()(double t) const {
    const double rate = 0.5 * Pf_ / (0.3 * s_);  // the first ramp's
    if (t < 0.3 * s_) return rate * t;
    if (t < settled()) return 0.5 * Pf_;
    const double t1 = settled() + 0.4 * Pf_ / rate;  // at 0.9 P_f
    if (t < t1) return 0.5 * Pf_ + rate * (t - settled());
    if (t < t1 + 0.3 * s_) return 0.9 * Pf_;
    return Pf_ * (0.9 + 0.2 * (t - t1 - 0.3 * s_) / s_);
  }
  double settled() const { return 0.8 * s_; }  // the end of phase 1
  double end() const { return 4.0 * s_; }      // the latest stop of phase 2

 private:
  double Pf_, s_;
};

// The example's run on springs: 2D, or the 3D strip of the scene's width (Dim = 3).
template <int Dim = 2>
RunResult run(const scenes::FloatingIceBeam& scene, const RunOptions& o) {
  RunResult r;
  r.l0 = scene.thickness / o.rows;
  r.lambda = scene.lambda();
  r.failure_load = scene.failure_load();
  r.omega0 = omega0(scene);
  const double time_scale = omega0(scenes::FloatingIceBeam{}) / r.omega0;  // 1 at h = 40 mm
  const ExampleLoad load(r.failure_load, time_scale);
  BeamOnFoundation<Dim> beam(scene, r.l0, o.fracture);
  auto& s = beam.solver();
  r.particles = s.particles().size();
  const auto wall = std::chrono::steady_clock::now();

  std::unique_ptr<PvdWriter> pvd;
  std::unique_ptr<CsvWriter> history;
  std::size_t frames = 0;
  if (!o.out.empty()) {
    mpsfsi_examples::make_output_folder(o.out);
    pvd = std::make_unique<PvdWriter>(o.out + "/ice.pvd");
    history = std::make_unique<CsvWriter>(
        o.out + "/history.csv", std::vector<std::string>{"t", "P", "end_deflection", "hetenyi_end_deflection",
                                                          "foundation_force", "failures", "cut_bonds"});
  }
  auto snapshot = [&] {
    if (!pvd) return;
    const std::string file = numbered_file_name("ice", frames++);
    write_vtu(o.out + "/" + file, s.output());
    pvd->add(s.time(), file);
  };
  const double horizon = o.fracture ? 2.6 * time_scale : load.settled();  // the expected end
  std::unique_ptr<ProgressReporter> progress;
  if (o.progress) progress = std::make_unique<ProgressReporter>(horizon);
  const double sample = 0.005 * time_scale;
  double next_snapshot = 0;
  auto advance = [&](double t_end) {
    while (s.time() < t_end - 1e-12) {
      const double t = std::min(t_end, s.time() + sample);
      beam.run_to(t, load);
      const double P = load(s.time());
      if (history)
        history->row({s.time(), P, beam.deflection()[0], scene.deflection(P, beam.column_x(0)), beam.foundation_force(),
                      static_cast<double>(s.failure_events()), static_cast<double>(s.cut_bonds())});
      // Snapshots every 0.05 time units, every 2 ms of the 0.1 s after the first failure.
      const double failed_for = s.first_failure_time() >= 0 ? s.time() - s.first_failure_time() : -1;
      const bool fracturing = failed_for >= 0 && failed_for < 0.1 * time_scale;
      if (s.time() >= next_snapshot - 1e-12 || (fracturing && next_snapshot > s.time() + 0.002)) {
        snapshot();
        next_snapshot = s.time() + (fracturing ? 0.002 : 0.05 * time_scale);
      }
      if (progress) progress->update(s.step_count(), std::min(s.time(), horizon));
      if (failed_for > o.after_failure * time_scale) return;
    }
  };

  advance(load.settled());
  r.deflection = check_deflection(beam, scene, load(s.time()));
  if (!o.out.empty()) {
    CsvWriter profile(o.out + "/deflection.csv", {"x", "w", "hetenyi_w"});
    for (std::size_t c = 0; c < r.deflection.w.size(); ++c)
      profile.row({r.deflection.x[c], r.deflection.w[c], scene.deflection(r.deflection.load, r.deflection.x[c])});
  }
  if (o.fracture) advance(load.end());
  if (progress) progress->finish();
  snapshot();
  r.steps = s.step_count();
  r.end_time = s.time();
  r.brk = read_break(s, wall);
  if (r.brk.failures > 0) r.brk.load_at_failure = Vec<2>(0, -load(r.brk.first_failure_time));
  r.wall_seconds = r.brk.wall_seconds;
  if (!o.out.empty() && r.brk.failures > 0) write_failures(o.out, s);
  return r;
}

}  // namespace floating_ice
