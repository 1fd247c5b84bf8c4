// SPDX-License-Identifier: BSD-3-Clause
// Three-point bending of an ice beam with brittle fracture (the paper's Table 1 protocol,
// docs/theory.md, section 6): sigma_f from Table 1 and E from Table 1 as the material or the apparent
// modulus (section 6.3), nu = 0.3, 917 kg/m3, span 0.18 m on two rigid supports, a rigid indenter at
// mid-span driven down at constant speed.
// Shared by examples/three_point_bending and the validation tests.
#pragma once

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <mpsfsi/fracture/fracture_process.hpp>
#include <mpsfsi/io/checkpoint.hpp>
#include <mpsfsi/io/csv_writer.hpp>
#include <mpsfsi/io/progress.hpp>
#include <mpsfsi/io/pvd_writer.hpp>
#include <mpsfsi/io/vtu_writer.hpp>
#include <mpsfsi/scenes/solid_block.hpp>
#include <mpsfsi/solid/elastic_solver.hpp>
#include <mpsfsi/solid/fragments.hpp>

#include "common/output_folder.hpp"
#include "common/run_checkpoints.hpp"

namespace bending {

// One row of the paper's Table 1: specimen width and height, measured peak load and mid-span
// deflection at the peak. E (eq 36), sigma_f (eq 37) and the flexural strain (eq 38, read as
// 6 h dd / L^2) follow, as recomputed in docs/theory.md, section 6.1.
struct IceBeamCase {
  std::string name;
  double width = 0, height = 0, peak_load = 0, deflection = 0;
  static constexpr double span = 0.18;
  double youngs_modulus() const { return span * span * span * peak_load / (4 * width * height * height * height * deflection); }
  double tensile_strength() const { return 3 * peak_load * span / (2 * width * height * height); }
  double flexural_strain() const { return 6 * height * deflection / (span * span); }
  // The material modulus: the E with which a Timoshenko beam (shear coefficient 5/6, the
  // rectangular section's; Timoshenko 1921, Cowper 1966) deflects as the specimen did,
  // E_app (1 + 2 (1 + nu) h^2 / (kappa L^2)) (docs/theory.md, section 6.3).
  double material_modulus(double poisson_ratio) const {
    constexpr double shear_coefficient = 5.0 / 6.0;
    return youngs_modulus() * (1 + 2 * (1 + poisson_ratio) * height * height / (shear_coefficient * span * span));
  }
};

inline std::vector<IceBeamCase> table1() {
  return {{"02", 0.082, 0.038, 500.1, 6.0e-4},
          {"03", 0.084, 0.044, 411.9, 4.0e-4},
          {"04", 0.081, 0.040, 588.4, 9.0e-4},
          {"05", 0.079, 0.039, 441.3, 1.0e-3},
          {"10", 0.082, 0.037, 323.6, 1.15e-3}};
}

// Which E the solid is given (docs/theory.md, section 6.3): the material modulus (default), or
// Table 1's apparent Euler-Bernoulli modulus as the paper does.
enum class Modulus { material, apparent };

struct Options {
  Modulus modulus = Modulus::material;
  double l0 = 0.002;        // target spacing; the beam height is made a whole number of spacings
  double speed = 0.02;      // indenter speed (m/s), reached after a smooth ramp
  double ramp_periods = 2;  // ramp length in periods of the beam's first bending mode
  double overhang = 0.01;   // beam length beyond each support (m)
  double roller_radius = 0.005;  // supports and indenter (m)
  double poisson_ratio = 0.3, density = 917;
  mpsfsi::PlaneModel plane_model = mpsfsi::PlaneModel::plane_stress;
  double courant = 0.4;
  double bond_viscosity = 0.2;  // damps the grid-scale ringing of bond cuts (SolidParameters)
  bool average_failure_stress = true;  // SolidParameters::average_failure_stress
  bool failure_stress_at_surface = true;  // SolidParameters::failure_stress_at_surface
  double contact_damping = 0;          // SolidParameters::contact_damping_ratio
  mpsfsi::CrackSide crack_side = mpsfsi::CrackSide::slab;  // SolidParameters::crack_side
  std::string out;          // output directory; empty: no files
  bool progress = false;
  // Checkpoints (examples/common/run_checkpoints.hpp): off unless `checkpoints` is set; then at
  // `checkpoint_every` (s; 0: only on Ctrl-C / SIGTERM), into `out`. `restart`: a checkpoint of
  // the same case and options to continue from.
  bool checkpoints = false;
  double checkpoint_every = 0;
  std::string restart;
};

// The Young's modulus the solid is given in case `c`.
inline double input_modulus(const IceBeamCase& c, const Options& o) {
  return o.modulus == Modulus::material ? c.material_modulus(o.poisson_ratio) : c.youngs_modulus();
}

struct HistoryRow {
  double t, indenter, deflection, bottom_deflection, load, sxx_top, sxx_bottom;
};

// The loading loop's own state, saved with the solver in each checkpoint so that a restarted run
// gives the same results and files as one run straight through.
struct LoopState {
  double peak_load = 0, deflection_at_peak = 0, bottom_deflection_at_peak = 0, indenter_at_peak = 0, time_at_peak = 0;
  double energy_at_failure = 0, indenter_work = 0, work_at_failure = 0, largest_balance = 0;
  double after_peak_low = -1, next_snapshot = 0;
  long long frames = 0;
  std::vector<double> frame_times;  // the PVD index
  std::vector<HistoryRow> history;

  template <class Archive>
  void checkpoint_state(Archive& a) {
    for (double* v : {&peak_load, &deflection_at_peak, &bottom_deflection_at_peak, &indenter_at_peak, &time_at_peak,
                      &energy_at_failure, &indenter_work, &work_at_failure, &largest_balance, &after_peak_low,
                      &next_snapshot})
      a.value(*v);
    a.value(frames);
    a.array(frame_times);
    // History rows through a flat copy (the archive takes vectors of numbers).
    std::vector<double> flat;
    for (const auto& h : history) flat.insert(flat.end(), {h.t, h.indenter, h.deflection, h.bottom_deflection, h.load, h.sxx_top, h.sxx_bottom});
    a.array(flat);
    if (flat.size() % 7 != 0) throw mpsfsi::InvalidInput("three_point_bending: the checkpoint's load history is damaged");
    history.clear();
    for (std::size_t k = 0; k < flat.size(); k += 7)
      history.push_back({flat[k], flat[k + 1], flat[k + 2], flat[k + 3], flat[k + 4], flat[k + 5], flat[k + 6]});
  }
};

struct Result {
  IceBeamCase input;
  double youngs_modulus = 0;      // the E the solid was given, Pa
  double l0 = 0;
  std::size_t particles = 0;
  double peak_load = 0;           // N (force per width times w in 2D)
  double deflection_at_peak = 0;  // mid-span, mid-height, relative to mid-height over the supports, m
  double bottom_deflection_at_peak = 0;  // the same along the bottom row, m
  double indenter_at_peak = 0;    // indenter travel, m
  double time_at_peak = 0, first_failure = -1, end_time = 0;
  double flexural_strain = 0;     // 6 h dd / L^2 with the simulated deflection
  double final_load_fraction = 1; // load at the end / peak load
  bool broken = false;            // the beam is in two pieces (detail::material_pieces)
  // Diagnostics of a beam that is still one piece: intact bonds stretched beyond 5 % (none in an
  // unbroken beam, whose strain stays below 0.5 %), and whether it is in two pieces without them.
  std::size_t overstretched_bonds = 0;
  bool broken_but_overstretched = false;
  double crack_offset = 0;        // largest |x| of a failed particle (reference), m
  // A broken beam's fracture surface, where each lattice row along x passes from one piece to
  // the other (reference configuration): its largest |x| (m), the number of such crossings (one
  // per row for a single surface), how many lie more than 2 l0 from the centre line, and rows.
  double fracture_surface_offset = -1;
  std::size_t fracture_surface_crossings = 0, fracture_surface_beyond_2l0 = 0, lattice_rows = 0;
  std::size_t rows_crossed_once = 0;  // rows with exactly one crossing
  double crack_start_x = 0, crack_start_y = 0;  // the first failed particle (reference), m
  double crack_top = 0;           // highest failed particle (reference), m
  // Energy balance after the first failure: the solid's total energy (kinetic, strain, contact)
  // minus the work the indenter has done on it since, at its largest, relative to the energy at
  // the first failure, minus one. After the first crack nothing else feeds energy in (bond
  // viscosity and cutting take it out), so this stays at or below zero up to the explicit
  // scheme's energy error; a refit that injects energy shows here (the shattered 1 mm beam: x2000).
  double energy_at_failure = 0;   // J per m of width in 2D, J in 3D
  double energy_rise_after_failure = 0;
  double wall_seconds = 0;
  int stop_code = 0;  // 128 + signal when stopped by Ctrl-C / SIGTERM (the result is then partial)
  std::vector<HistoryRow> history;
  double error() const { return flexural_strain / input.flexural_strain() - 1; }
};

namespace detail {

// Stretch |r_ij| / |r0_ij| - 1 of bond b from particle i.
template <class Solver>
double stretch(const Solver& s, std::size_t i, mpsfsi::Offset b) {
  const auto j = static_cast<std::size_t>(s.bonds().neighbor(b));
  return (s.particles().positions()[j] - s.particles().positions()[i]).norm() / s.bonds().r0(b).norm() - 1;
}

// Pieces of the beam with more than a tenth of its particles (loose particles and chips at the
// crack faces are left out): a broken beam has two. The beam is particles [0, beam_count); the
// rollers are separate bodies with no bonds to it, so they are fragments of their own.
inline std::size_t large_pieces(const mpsfsi::Fragments& f, std::size_t beam_count) {
  // Labels follow each fragment's first particle and the beam comes first, so the beam's
  // fragments are the labels below the first roller particle's.
  const std::size_t beam_labels =
      beam_count < f.label.size() ? static_cast<std::size_t>(f.label[beam_count]) : f.count();
  std::size_t n = 0;
  for (std::size_t k = 0; k < beam_labels; ++k) n += f.sizes[k] > beam_count / 10 ? 1 : 0;
  return n;
}

// The beam's material as pieces: the bonds between particles that did not fail with
// CrackSide::slab. Such a particle is cut out of the solid and becomes the crack (docs/theory.md,
// section 5.3). Its strip keeps its bonds along the slab and to the material at the strip's ends,
// so strips that meet (two cracks joined in the top row, say) can link the two faces while
// carrying nothing across. `also(i, b)` may leave further bonds out.
template <class Solver, class KeepBond>
mpsfsi::Fragments material_pieces(const Solver& s, mpsfsi::CrackSide side, KeepBond also) {
  std::vector<char> crack(s.particles().size(), 0);
  if (side == mpsfsi::CrackSide::slab)
    for (const auto& event : s.failure_log()) crack[event.particle] = 1;
  return mpsfsi::find_fragments(s.bonds(), [&](std::size_t i, mpsfsi::Offset b) {
    return crack[i] == 0 && crack[static_cast<std::size_t>(s.bonds().neighbor(b))] == 0 && also(i, b);
  });
}
template <class Solver>
mpsfsi::Fragments material_pieces(const Solver& s, mpsfsi::CrackSide side) {
  return material_pieces(s, side, [](std::size_t, mpsfsi::Offset) { return true; });
}

}  // namespace detail

// Runs one case. Dim 2: plane stress or strain per unit width, loads scaled by w. Dim 3: the
// beam's real width (rounded to whole spacings, loads rescaled to the nominal width).
template <int Dim>
Result run(const IceBeamCase& c, const Options& o) {
  using namespace mpsfsi;
  using vec = Vec<Dim>;
  const auto wall0 = std::chrono::steady_clock::now();
  Result r;
  r.input = c;
  r.youngs_modulus = input_modulus(c, o);
  const int layers = std::max(2, static_cast<int>(std::lround(c.height / o.l0)));
  const double l0 = c.height / layers;
  r.l0 = l0;
  const double span = IceBeamCase::span;
  const int half_columns = static_cast<int>(std::lround((span / 2 + o.overhang) / l0 - 0.5));
  const double half_length = (half_columns + 0.5) * l0;
  const int z_layers = Dim == 3 ? std::max(1, static_cast<int>(std::lround(c.width / l0))) : 1;
  const double depth = Dim == 3 ? z_layers * l0 : c.width;  // modelled width
  vec lower = vec::Zero(), upper = vec::Zero();
  lower[0] = -half_length;
  upper[0] = half_length;
  upper[1] = c.height;
  if constexpr (Dim == 3) upper[2] = depth;
  ParticleSet<Dim> set = scenes::material_block<Dim>(lower, upper, l0);
  const std::size_t beam_count = set.size();
  std::vector<std::int32_t> body(beam_count, 0);
  // Rigid rollers of radius `roller_radius`: two supports under x = -L/2 and +L/2 and the
  // indenter above x = 0, each a half-ring of particles (arc spacing about 0.6 l0, so that the
  // contact spreads over the beam particles it meets), one contact distance l0 from the beam's
  // outer rows, replicated across the width in 3D.
  std::vector<std::size_t> indenter;
  auto add_roller = [&](double cx, double cy, double facing, int id, bool is_indenter) {
    // An even number of segments puts a particle at the pole, exactly one contact distance from
    // the beam: with a gap the indenter strikes the beam, which (held by nothing but contact)
    // bounces between rollers and indenter.
    int segments = std::max(4, static_cast<int>(std::ceil(M_PI * o.roller_radius / (0.6 * l0))));
    segments += segments % 2;
    for (int k = 0; k < z_layers; ++k)
      for (int m = 0; m <= segments; ++m) {
        const double angle = M_PI * m / segments;  // 0..pi across the half facing the beam
        vec p = vec::Zero();
        p[0] = cx + o.roller_radius * std::cos(angle);
        p[1] = cy + facing * o.roller_radius * std::sin(angle);
        if constexpr (Dim == 3) p[2] = (k + 0.5) * l0;
        const auto i = static_cast<std::size_t>(set.add(p, ParticleKind::solid));
        body.push_back(id);
        if (is_indenter) indenter.push_back(i);
      }
  };
  add_roller(-span / 2, -l0 / 2 - o.roller_radius, 1, 1, false);
  add_roller(span / 2, -l0 / 2 - o.roller_radius, 1, 2, false);
  add_roller(0, c.height + l0 / 2 + o.roller_radius, -1, 3, true);

  SolidParameters<Dim> p;
  p.l0 = l0;
  p.density = o.density;
  p.youngs_modulus = r.youngs_modulus;
  p.poisson_ratio = o.poisson_ratio;
  p.plane_model = o.plane_model;
  p.tensile_strength = c.tensile_strength();
  p.courant = o.courant;
  p.bond_viscosity = o.bond_viscosity;
  p.average_failure_stress = o.average_failure_stress;
  p.failure_stress_at_surface = o.failure_stress_at_surface;
  p.contact_damping_ratio = o.contact_damping;
  p.crack_side = o.crack_side;
  p.max_courant = std::max(p.max_courant, o.courant);
  ElasticSolver<Dim, BrittleSolidPolicies<Dim>> s(set, p, body);
  for (std::size_t i = beam_count; i < set.size(); ++i) s.clamp(i);
  r.particles = set.size();

  // Probes: the bottom and top particles of the centre column (x = 0), at mid-width in 3D.
  // Probes interpolate the displacement bilinearly between the (reference) lattice particles
  // around a point of the x-y plane (at mid-width in 3D, averaged over the two middle layers).
  struct Probe {
    std::vector<std::pair<std::size_t, double>> terms;
  };
  auto probe = [&](double x, double y) {
    Probe pr;
    const double fx = (x + half_length) / l0 - 0.5, fy = y / l0 - 0.5;
    const int ix = std::clamp(static_cast<int>(std::floor(fx)), 0, 2 * half_columns - 1);
    const int iy = std::clamp(static_cast<int>(std::floor(fy)), 0, layers - 2);
    const double ax = std::clamp(fx - ix, 0.0, 1.0), ay = std::clamp(fy - iy, 0.0, 1.0);
    const int columns = 2 * half_columns + 1;
    std::vector<int> zs{0};
    if constexpr (Dim == 3) zs = z_layers % 2 ? std::vector<int>{z_layers / 2} : std::vector<int>{z_layers / 2 - 1, z_layers / 2};
    for (const int z : zs)
      for (int dy = 0; dy < 2; ++dy)
        for (int dx = 0; dx < 2; ++dx) {
          const double w = (dx ? ax : 1 - ax) * (dy ? ay : 1 - ay) / static_cast<double>(zs.size());
          const auto i = static_cast<std::size_t>((z * layers + iy + dy) * columns + ix + dx);
          if (w > 0) pr.terms.emplace_back(i, w);
        }
    return pr;
  };
  auto sag = [&](const Probe& pr) {
    double v = 0;
    for (const auto& [i, w] : pr.terms) v += w * (s.reference_positions()[i] - s.particles().positions()[i])[1];
    return v;
  };
  // Deflection at mid-span relative to the beam over the supports: at the bottom fibre's row and
  // at mid-height (the beam-theory deflection of the neutral axis); the first is what a gauge
  // under the beam reads, the second excludes the local contact indentation at the supports.
  const Probe bottom_mid = probe(0, l0 / 2), bottom_left = probe(-span / 2, l0 / 2), bottom_right = probe(span / 2, l0 / 2);
  const Probe axis_mid = probe(0, c.height / 2), axis_left = probe(-span / 2, c.height / 2), axis_right = probe(span / 2, c.height / 2);
  // Stress probes: the bottom and top particles of the centre column (mid-width in 3D).
  auto nearest = [&](double y) {
    vec target = vec::Zero();
    target[1] = y;
    if constexpr (Dim == 3) target[2] = depth / 2;
    std::size_t best = 0;
    for (std::size_t i = 0; i < beam_count; ++i)
      if ((set.positions()[i] - target).norm() < (set.positions()[best] - target).norm()) best = i;
    return best;
  };
  const std::size_t bottom = nearest(l0 / 2), top = nearest(c.height - l0 / 2);
  // The rollers are frictionless, so nothing holds the beam sideways: the top particle of the
  // centre column is kept from moving along x (no reaction under symmetric loading).
  s.support(top, vec::UnitX());

  // Loading: v(t) = speed (1 - cos(pi t / t_r)) / 2 up to t_r, then constant; t_r a few periods
  // of the first bending mode (simply supported Euler-Bernoulli beam with Table 1's E, whichever
  // modulus the solid is given, so that the protocol is the same for both) to keep it quasi-static.
  const double inertia = c.height * c.height * c.height / 12;
  const double omega1 = std::pow(M_PI / span, 2) * std::sqrt(c.youngs_modulus() * inertia / (o.density * c.height));
  const double ramp = o.ramp_periods * 2 * M_PI / omega1;
  // The expected failure time if the beam behaved as Table 1 says, to size the run.
  const double expected = c.deflection / o.speed + ramp / 2;
  const double t_max = 3 * expected;
  const double scale = Dim == 2 ? c.width : c.width / depth;  // to the specimen's force in N

  std::unique_ptr<PvdWriter> pvd;
  LoopState st;
  if (!o.out.empty()) {
    mpsfsi_examples::make_output_folder(o.out);
    pvd = std::make_unique<PvdWriter>(o.out + "/case" + c.name + ".pvd");
  }
  std::unique_ptr<ProgressReporter> progress;
  // Progress runs to the failure plus the fracture's few milliseconds: given the apparent modulus
  // the simulated beam deflects 13-20 % more than Table 1's, so it fails later than `expected`
  // (3D case 02 at l0 = 2 mm: about 1.4 expected).
  const double progress_horizon = 1.6 * expected;
  if (o.progress) {
    progress = std::make_unique<ProgressReporter>(progress_horizon);
    progress->set_label("case " + c.name);
  }
  const auto snapshot_name = [&](long long frame) { return numbered_file_name("case" + c.name, static_cast<std::size_t>(frame)); };
  auto snapshot = [&] {
    if (!pvd) return;
    const std::string file = snapshot_name(st.frames++);
    write_vtu(o.out + "/" + file, s.output());
    pvd->add(s.time(), file);
    st.frame_times.push_back(s.time());
  };
  // The indenter's lowest particle (angle pi/2) is its reference point for the travel.
  std::size_t lowest = indenter[0];
  for (const auto i : indenter)
    if (s.particles().positions()[i][1] < s.particles().positions()[lowest][1]) lowest = i;
  const double y_indenter0 = s.particles().positions()[lowest][1];
  if (o.restart.empty()) {
    snapshot();
  } else {
    read_checkpoint(o.restart, s, st);
    for (long long k = 0; pvd && k < st.frames; ++k) pvd->add(st.frame_times[static_cast<std::size_t>(k)], snapshot_name(k));
    std::printf("case %s: continuing from %s at step %lld, t = %g s\n", c.name.c_str(), o.restart.c_str(), s.step_count(),
                s.time());
  }
  std::optional<mpsfsi_examples::RunCheckpoints> checkpoints;
  if (o.checkpoints) checkpoints.emplace(o.out, o.checkpoint_every, "checkpoint_case" + c.name);
  const long long history_every = std::max(1LL, static_cast<long long>(expected / 2000 / s.dt()));
  for (;;) {
    const double t = s.time();
    if (checkpoints && (checkpoints->due(t) || checkpoints->stop_requested())) {
      const std::string path = checkpoints->write(s, s.step_count(), t, st);
      std::fprintf(stderr, "checkpoint: %s (t = %g s)\n", path.c_str(), t);
      if (checkpoints->stop_requested()) {
        std::fprintf(stderr, "three_point_bending: stopped by a signal; continue with --case %s --restart %s\n",
                     c.name.c_str(), path.c_str());
        r.stop_code = checkpoints->stop_exit_code();
        return r;
      }
    }
    const double v = t < ramp ? o.speed * 0.5 * (1 - std::cos(M_PI * t / ramp)) : o.speed;
    vec vel = vec::Zero();
    vel[1] = -v;
    for (const auto i : indenter) s.prescribe_velocity(i, vel);
    s.step();
    // Load: the beam pushes the indenter up through contact.
    double load = 0;
    for (const auto i : indenter) load += s.internal_force(i)[1];
    st.indenter_work += load * v * s.last_dt();  // the indenter moves down at v against the beam's push
    load *= scale;
    if (s.first_failure_time() >= 0 && (st.energy_at_failure == 0 || s.step_count() % 10 == 0)) {
      const double balance = s.total_energy() - (st.indenter_work - st.work_at_failure);
      if (st.energy_at_failure == 0) {
        st.energy_at_failure = st.largest_balance = s.total_energy();
        st.work_at_failure = st.indenter_work;
      }
      st.largest_balance = std::max(st.largest_balance, balance);
    }
    const double deflection = sag(axis_mid) - 0.5 * (sag(axis_left) + sag(axis_right));
    const double bottom_deflection = sag(bottom_mid) - 0.5 * (sag(bottom_left) + sag(bottom_right));
    const double travel = y_indenter0 - s.particles().positions()[lowest][1];
    // The peak: the largest load up to the first crack. The crack then runs through the beam in
    // about 0.2 ms; load read during that run and after it is the dynamics of the pieces
    // (recorded in the history, not taken as the strength).
    const bool before_fracture = s.first_failure_time() < 0;
    if (before_fracture && load > st.peak_load) {
      st.peak_load = load;
      st.deflection_at_peak = deflection;
      st.bottom_deflection_at_peak = bottom_deflection;
      st.indenter_at_peak = travel;
      st.time_at_peak = s.time();
    }
    // History: evenly in time, and every 10th step once cracks run (to resolve the load drop).
    if (s.step_count() % history_every == 0 || (s.cut_bonds() > 0 && s.step_count() % 10 == 0)) {
      const auto& sigma = s.stresses();
      st.history.push_back({s.time(), travel, deflection, bottom_deflection, load, sigma[top](0, 0), sigma[bottom](0, 0)});
    }
    // Snapshots: 20 over the loading, then every 0.05 ms for the first millisecond of fracture.
    const bool fracturing = s.first_failure_time() >= 0 && s.time() < s.first_failure_time() + 1e-3;
    if (pvd && s.time() >= st.next_snapshot) {
      snapshot();
      st.next_snapshot = s.time() + (fracturing ? 5e-5 : expected / 20);
    } else if (fracturing && st.next_snapshot > s.time() + 5e-5) {
      st.next_snapshot = s.time();  // the first crack: switch to the fine cadence at once
    }
    if (progress) progress->update(s.step_count(), std::min(s.time(), progress_horizon));
    // Stop when the beam is in two pieces and the load has stayed below 2 % of the peak for
    // 0.5 ms, or 5 ms after the first crack, or at three times the expected failure time.
    if (s.first_failure_time() >= 0 && load < 0.02 * st.peak_load) {
      if (st.after_peak_low < 0) st.after_peak_low = s.time();
      if (s.time() - st.after_peak_low > 5e-4 && s.step_count() % 50 == 0) {
        if (detail::large_pieces(detail::material_pieces(s, o.crack_side), beam_count) >= 2) break;
      }
    } else {
      st.after_peak_low = -1;
    }
    if (s.time() > t_max || (s.first_failure_time() >= 0 && s.time() > s.first_failure_time() + 5e-3)) break;
  }
  if (progress) progress->finish();
  snapshot();
  r.peak_load = st.peak_load;
  r.deflection_at_peak = st.deflection_at_peak;
  r.bottom_deflection_at_peak = st.bottom_deflection_at_peak;
  r.indenter_at_peak = st.indenter_at_peak;
  r.time_at_peak = st.time_at_peak;
  r.energy_at_failure = st.energy_at_failure;
  r.history = st.history;
  r.end_time = s.time();
  r.first_failure = s.first_failure_time();
  if (r.energy_at_failure > 0) r.energy_rise_after_failure = st.largest_balance / r.energy_at_failure - 1;
  r.flexural_strain = 6 * c.height * r.deflection_at_peak / (span * span);
  double last_load = 0;
  for (const auto i : indenter) last_load += s.internal_force(i)[1];
  r.final_load_fraction = last_load * scale / r.peak_load;
  const Fragments fragments = detail::material_pieces(s, o.crack_side);
  r.broken = detail::large_pieces(fragments, beam_count) >= 2;
  constexpr double overstretched = 0.05;
  if (!r.broken) {
    std::unique_ptr<CsvWriter> open_bonds;
    if (!o.out.empty())
      open_bonds = std::make_unique<CsvWriter>(
          o.out + "/case" + c.name + "_overstretched_bonds.csv",
          std::vector<std::string>{"i", "j", "x0_i", "y0_i", "z0_i", "x0_j", "y0_j", "z0_j", "stretch", "intact_i",
                                   "intact_j"});
    for (std::size_t i = 0; i < beam_count; ++i)
      for (Offset b = s.bonds().begin(i); b < s.bonds().end(i); ++b) {
        const auto j = static_cast<std::size_t>(s.bonds().neighbor(b));
        if (j <= i || j >= beam_count || !s.bonds().intact(b)) continue;
        const double e = detail::stretch(s, i, b);
        if (e <= overstretched) continue;
        ++r.overstretched_bonds;
        const vec xi = s.reference_positions()[i], xj = s.reference_positions()[j];
        if (open_bonds)
          open_bonds->row({double(i), double(j), xi[0], xi[1], Dim == 3 ? xi[Dim - 1] : 0.0, xj[0], xj[1],
                           Dim == 3 ? xj[Dim - 1] : 0.0, e, double(s.bonds().intact_count(i)),
                           double(s.bonds().intact_count(j))});
      }
    const auto keep = [&](std::size_t i, Offset b) { return detail::stretch(s, i, b) <= overstretched; };
    r.broken_but_overstretched = detail::large_pieces(detail::material_pieces(s, o.crack_side, keep), beam_count) >= 2;
  }
  // The crack path: where particles failed, in the reference configuration.
  if (!s.failure_log().empty()) {
    const vec first = s.reference_positions()[s.failure_log().front().particle];
    r.crack_start_x = first[0];
    r.crack_start_y = first[1];
    for (const auto& event : s.failure_log()) {
      const vec x = s.reference_positions()[event.particle];
      r.crack_offset = std::max(r.crack_offset, std::abs(x[0]));
      r.crack_top = std::max(r.crack_top, x[1]);
    }
  }
  // The fracture surface of a broken beam, line by line: along every lattice row in x (one y,
  // one z), skipping particles that are not in one of the two large pieces (chips, particles
  // that lost every bond, and the strip of a CrackSide::slab crack's cut-out particles), it
  // lies halfway between the last particle of one piece and the first of the other. A failure
  // off that surface cuts bonds without separating the beam there.
  if (r.broken) {
    const auto is_large = [&](std::size_t i) {
      return fragments.sizes[static_cast<std::size_t>(fragments.label[i])] > beam_count / 10;
    };
    const int columns = 2 * half_columns + 1;
    for (int k = 0; k < z_layers; ++k)
      for (int iy = 0; iy < layers; ++iy) {
        const auto first = static_cast<std::size_t>((k * layers + iy) * columns);
        std::size_t last_large = beam_count, crossings = 0;
        for (int ix = 0; ix < columns; ++ix) {
          const std::size_t i = first + static_cast<std::size_t>(ix);
          if (!is_large(i)) continue;
          if (last_large < beam_count && fragments.label[i] != fragments.label[last_large]) {
            const double x = 0.5 * (s.reference_positions()[i][0] + s.reference_positions()[last_large][0]);
            r.fracture_surface_offset = std::max(r.fracture_surface_offset, std::abs(x));
            ++r.fracture_surface_crossings;
            ++crossings;
            if (std::abs(x) > 2 * l0 + 1e-12) ++r.fracture_surface_beyond_2l0;
          }
          last_large = i;
        }
        r.rows_crossed_once += crossings == 1 ? 1 : 0;
      }
    r.lattice_rows = static_cast<std::size_t>(z_layers * layers);
  }
  if (!o.out.empty()) {
    CsvWriter history(o.out + "/case" + c.name + "_history.csv",
                      {"t", "indenter_m", "deflection_m", "bottom_deflection_m", "load_N", "sxx_top_Pa", "sxx_bottom_Pa"});
    for (const auto& h : r.history)
      history.row({h.t, h.indenter, h.deflection, h.bottom_deflection, h.load, h.sxx_top, h.sxx_bottom});
    // Every failure in order: when, which particle (reference position), its sigma_1 and the
    // crack normal.
    CsvWriter failures(o.out + "/case" + c.name + "_failures.csv",
                       {"t", "particle", "x0", "y0", "z0", "sigma1_Pa", "nx", "ny", "nz"});
    for (const auto& event : s.failure_log()) {
      const vec x = s.reference_positions()[event.particle];
      failures.row({event.time, double(event.particle), x[0], x[1], Dim == 3 ? x[Dim - 1] : 0.0, event.sigma1,
                    event.normal[0], event.normal[1], Dim == 3 ? event.normal[Dim - 1] : 0.0});
    }
    CsvWriter final_state(o.out + "/case" + c.name + "_final.csv",
                          {"x", "y", "z", "x0", "y0", "z0", "damage", "sxx_Pa", "fragment"});
    const auto& out = s.output();
    const auto& sigma = s.stresses();
    for (std::size_t i = 0; i < beam_count; ++i) {
      const vec x = out.positions()[i], x0 = s.reference_positions()[i];
      final_state.row({x[0], x[1], Dim == 3 ? x[Dim - 1] : 0.0, x0[0], x0[1], Dim == 3 ? x0[Dim - 1] : 0.0,
                       s.bonds().damage(i), sigma[i](0, 0), double(fragments.label[i])});
    }
  }
  r.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
  return r;
}

}  // namespace bending
