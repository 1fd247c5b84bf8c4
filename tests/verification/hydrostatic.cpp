// SPDX-License-Identifier: BSD-3-Clause
// Hydrostatic tank: a water column at rest in an open tank, against rho g (H - y).
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "mpsfsi/fluid/fluid_solver.hpp"
#include "mpsfsi/fluid/water_under_structure.hpp"
#include "mpsfsi/scenes/floating_ice_beam.hpp"
#include "mpsfsi/scenes/tank.hpp"
#include "support/tolerance.hpp"

using namespace mpsfsi;

namespace {

template <int Dim, class Policies = FluidDefaults<Dim>>
void run_hydrostatic(double width, double depth, double l0, double settle, double average, double dt,
                     WallCondition walls = WallCondition::wall_rows, bool density_term_compression_only = true) {
  ParticleSet<Dim> set;
  Vec<Dim> tank = Vec<Dim>::Constant(width);
  tank[Dim - 1] = 1.5 * depth;
  Vec<Dim> water = Vec<Dim>::Constant(width);
  water[Dim - 1] = depth;
  scenes::add_block<Dim, double>(set, Vec<Dim>::Zero(), water, l0, ParticleKind::fluid);
  scenes::add_tank<Dim, double>(set, tank, l0);
  FluidParameters<Dim> p;
  p.l0 = l0;
  p.dt = dt;
  p.wall_condition = walls;
  p.density_term_compression_only = density_term_compression_only;
  FluidSolver<Dim, Policies> solver(std::move(set), p);

  solver.advance_to(settle);
  // Time-average the pressure of every fluid particle over `average` seconds.
  const auto& ps = solver.particles();
  std::vector<double> mean(ps.size(), 0.0);
  int samples = 0;
  while (solver.time() < settle + average - 1e-9) {
    solver.step();
    for (std::size_t i = 0; i < ps.size(); ++i) mean[i] += solver.pressure()[i];
    ++samples;
  }
  const double rho_g = p.density * p.gravity.norm();
  // The pressure along the depth: time-averaged pressures averaged over layers one spacing
  // thick, against rho g (H - y) at the layer's mean height. The worst single particle is
  // reported too.
  const auto layers = static_cast<std::size_t>(std::llround(depth / l0));
  std::vector<double> layer_p(layers, 0.0), layer_y(layers, 0.0), layer_n(layers, 0.0);
  double worst_particle = 0, volume_ratio = 0;
  std::size_t fluid = 0, escaped = 0;
  for (std::size_t i = 0; i < ps.size(); ++i) {
    if (ps.kinds()[i] != ParticleKind::fluid) continue;
    ++fluid;
    const Vec<Dim>& x = ps.positions()[i];
    bool inside = x[Dim - 1] > 0 && x[Dim - 1] < 1.5 * depth;
    for (int k = 0; k < Dim - 1; ++k) inside = inside && x[k] > 0 && x[k] < width;
    escaped += inside ? 0 : 1;
    const double y = x[Dim - 1];
    if (y > 0.8 * depth || y < 0) continue;
    const double p_mean = mean[i] / samples;
    worst_particle = std::max(worst_particle, std::abs(p_mean - rho_g * (depth - y)) / (rho_g * depth));
    const auto layer = std::min(layers - 1, static_cast<std::size_t>(y / l0));
    layer_p[layer] += p_mean;
    layer_y[layer] += y;
    layer_n[layer] += 1;
  }
  double worst = 0;
  for (std::size_t l = 0; l < layers; ++l) {
    if (layer_n[l] == 0) continue;
    const double y = layer_y[l] / layer_n[l];
    worst = std::max(worst, std::abs(layer_p[l] / layer_n[l] - rho_g * (depth - y)) / (rho_g * depth));
  }
  // Volume: the column height in a tank of fixed width, from the highest particle of each
  // lateral column (half a spacing below the surface). n0 / <n> over particles with a full neighbourhood is reported too, but
  // disorder alone shifts n by a per cent or so, so it is no measure of volume to assert on.
  const double margin = p.re_laplacian() + l0;
  double n_sum = 0;
  std::size_t n_count = 0;
  // Highest particle in each lateral column of width l0; their mean + l0/2 is the surface.
  const auto columns = static_cast<std::size_t>(std::llround(width / l0));
  std::vector<double> column_top(Dim == 3 ? columns * columns : columns, -1.0);
  for (std::size_t i = 0; i < ps.size(); ++i) {
    if (ps.kinds()[i] != ParticleKind::fluid) continue;
    const Vec<Dim>& x = ps.positions()[i];
    bool interior = x[Dim - 1] > margin && x[Dim - 1] < depth - margin;
    for (int k = 0; k < Dim - 1; ++k) interior = interior && x[k] > margin && x[k] < width - margin;
    if (interior) {
      n_sum += solver.number_density_field()[i];
      ++n_count;
    }
    std::size_t c = 0;
    for (int k = Dim - 2; k >= 0; --k)
      c = c * columns + std::min(columns - 1, static_cast<std::size_t>(std::max(0.0, x[k] / l0)));
    column_top[c] = std::max(column_top[c], x[Dim - 1]);
  }
  volume_ratio = solver.density_constants().n0 / (n_sum / n_count);
  double top_sum = 0;
  for (double t : column_top) top_sum += t;
  const double surface_height = top_sum / static_cast<double>(column_top.size()) + 0.5 * l0;
  MESSAGE(Dim << "D hydrostatic tank, " << fluid << " fluid particles, " << solver.step_count()
              << " steps: pressure profile, worst layer |<P> - rho g (H - y)| / (rho g H) over the lower 80 % = "
              << worst << " (worst single particle " << worst_particle << "), volume ratio n0/<n> " << volume_ratio
              << ", mean surface height / H " << surface_height / depth
              << ", last PPE " << solver.last_solve().iterations << " iterations");
  CHECK(escaped == 0);
  CHECK(worst < 0.03);
  // Volume: the column height in a tank of fixed width, within 1 %: an incompressible column keeps
  // its height, and 1 % of H is 0.4 l0 (2D) and 0.3 l0 (3D) (measured 1.005 H and 0.993 H).
  CHECK(test::within_relative(surface_height, depth, 0.01));
}

// Water under a fixed lid: the floating ice beam's water (scenes::FloatingIceBeam at l0 = 10 mm,
// 0.25 m deep, 1.5 m of lid, open water only beyond the lid's far end) with the beam's particles
// laid out as the FSI coupler lays out a structure (surface rows wall, the rest dummy; the end
// against the tank wall covered, so dummy). At rest the lid's wall particles carry
// rho g (level - y) with `level` the open water's surface. Over [settle, window]: the mean lid
// load relative to that, and the steps with a lid particle at the free surface; over the whole
// run (to `end`): the first time a lid particle is at the free surface, where along the lid
// (the smallest and largest x of those at the free surface then; the lid's closed end is at the
// tank wall, x = 0), the fastest fluid, the first time water is above the lid's top face (it came
// over the lid's far end), and the fluid particles under the lid at the start and the end (below
// its bottom, more than 2 l0 from its far end), and how far the open water's surface rose (the
// mean over its columns of the highest fluid particle, from the start to the end; the water
// under the lid can only push it up by taking more room or losing particles). A run the solver
// stops (a blow-up, a step above the stability limit) ends there: `stopped` is the time of the
// last completed step and `stop` the solver's message.
struct LidResult {
  double load_ratio = 0, first_parted = -1, first_parted_from = -1, first_parted_to = -1, fastest = 0;
  double first_over = -1;  // the first time a fluid particle is above the lid's top face
  std::size_t under_start = 0, under_end = 0;  // fluid particles under the lid at the start and the end
  double open_rise = 0;                        // rise of the open water's surface from the start to the end, m
  int steps_parted = 0, steps = 0;
  double stopped = -1;
  std::string stop;
};

template <class Policies = FluidDefaults<2>>
LidResult water_under_lid(double lid_length, double l0, double settle, double window, double end, double dt,
                          WallCondition walls, bool density_term_compression_only = true) {
  scenes::FloatingIceBeam scene;
  scene.beam_length = lid_length;
  scene.thickness = 8 * l0;
  auto set = scene.fluid_particles(l0);
  std::vector<std::size_t> end_column;
  const auto lid = scene.beam_particles(l0, end_column);
  const double yb = scene.beam_bottom(l0), top = yb + scene.thickness, L = scene.beam_length_for(l0);
  const std::size_t first = set.size();
  for (const auto& x : lid.positions()) {
    const bool surface = x[1] < yb + l0 || x[1] > top - l0 || x[0] > L - l0;
    set.add(x, surface ? ParticleKind::wall : ParticleKind::dummy);
  }
  FluidParameters<2> p;
  p.l0 = l0;
  p.dt = dt;
  p.wall_condition = walls;
  p.density_term_compression_only = density_term_compression_only;
  FluidSolver<2, Policies> solver(std::move(set), p);
  const double rho_g = p.density * p.gravity.norm();
  const double hydrostatic = rho_g * (scene.open_water_level(l0) - (yb + 0.5 * l0)) * L;  // per unit width
  LidResult r;
  auto count_under = [&](const ParticleSet<2>& ps) {
    std::size_t count = 0;
    for (std::size_t i = 0; i < ps.size(); ++i)
      if (ps.kinds()[i] == ParticleKind::fluid && ps.positions()[i][1] < yb && ps.positions()[i][0] < L - 2 * l0)
        ++count;
    return count;
  };
  const double tank_end = scene.tank_length(l0);
  auto open_level = [&](const ParticleSet<2>& ps) {
    const auto columns = static_cast<std::size_t>(std::llround((tank_end - L) / l0));
    std::vector<double> column_top(columns, -1.0);
    for (std::size_t i = 0; i < ps.size(); ++i) {
      const Vec<2>& x = ps.positions()[i];
      if (ps.kinds()[i] != ParticleKind::fluid || x[0] <= L) continue;
      const auto c = std::min(columns - 1, static_cast<std::size_t>((x[0] - L) / l0));
      column_top[c] = std::max(column_top[c], x[1]);
    }
    double sum = 0;
    for (double top_of_column : column_top) sum += top_of_column;
    return sum / static_cast<double>(columns);
  };
  r.under_start = count_under(solver.particles());
  const double open_start = open_level(solver.particles());
  double load_sum = 0;
  while (solver.time() < end - 1e-9) {
    try {
      solver.step();
    } catch (const SimulationError& e) {
      r.stopped = solver.time();
      r.stop = e.what();
      break;
    }
    const auto& ps = solver.particles();
    double load = 0;
    bool parted = false;
    double parted_from = -1, parted_to = -1;
    for (std::size_t i = 0; i < ps.size(); ++i) {
      if (ps.kinds()[i] == ParticleKind::fluid) {
        r.fastest = std::max(r.fastest, ps.velocities()[i].norm());
        if (r.first_over < 0 && ps.positions()[i][1] > top) r.first_over = solver.time();
      }
      if (i < first || ps.kinds()[i] != ParticleKind::wall || std::abs(ps.positions()[i][1] - (yb + 0.5 * l0)) > 1e-9)
        continue;
      load += solver.pressure()[i] * l0;
      if (solver.free_surface()[i] != 0) {
        const double at = ps.positions()[i][0];
        parted_from = parted ? std::min(parted_from, at) : at;
        parted_to = parted ? std::max(parted_to, at) : at;
        parted = true;
      }
    }
    if (parted && r.first_parted < 0) {
      r.first_parted = solver.time();
      r.first_parted_from = parted_from;
      r.first_parted_to = parted_to;
    }
    if (solver.time() < settle - 1e-9 || solver.time() > window + 1e-9) continue;
    load_sum += load;
    r.steps_parted += parted ? 1 : 0;
    ++r.steps;
  }
  r.load_ratio = r.steps > 0 ? load_sum / r.steps / hydrostatic : 0.0;
  r.under_end = count_under(solver.particles());
  r.open_rise = open_level(solver.particles()) - open_start;
  return r;
}

// Water under a lid of `lid_length` with the settings for water under a structure, to 2 s: the
// checks of the 1.5 m case below. The step is 2 ms at l0 = 10 mm and scales with l0 (the same
// Courant number for the same flow).
template <class Policies = WaterUnderStructure<2>>
void check_water_under_lid_under_structure(double lid_length, double l0 = 0.01, double end = 2.0) {
  const double dt = 2e-3 * l0 / 0.01;
  const auto r = water_under_lid<Policies>(lid_length, l0, 0.3, end, end, dt, WallCondition::neumann, false);
  scenes::FloatingIceBeam scene;
  scene.thickness = 8 * l0;
  const double head = scene.open_water_level(l0) - (scene.beam_bottom(l0) + 0.5 * l0);
  const double offset_reference = (head - 0.5 * l0) / head;  // relative to the plain hydrostatic load
  const bool own_value = Policies::pressure_gradient_reference == GradientReference::own_value;
  MESSAGE("settings for water under a structure" << std::string(own_value ? " with the own-value gradient" : "")
          << ": water under a " << lid_length << " m lid, l0 = " << 1e3 * l0 << " mm: mean lid load over 0.3-"
          << (r.stopped >= 0 ? r.stopped : end) << " s / hydrostatic = " << r.load_ratio
          << " (with P = 0 on the surface particles: " << offset_reference
          << "), steps with a lid particle at the free surface: " << r.steps_parted << " of " << r.steps
          << "; first parting at t = " << r.first_parted << " s, fastest fluid " << r.fastest << " m/s"
          << "; water over the lid's top first at t = " << r.first_over << " s (-1: never); fluid particles "
          << "under the lid " << r.under_start << " at the start, " << r.under_end << " at the end"
          << "; the open water's surface rose by " << r.open_rise / l0 << " l0"
          << (r.stopped >= 0 ? "; stopped after t = " + std::to_string(r.stopped) + " s: " + r.stop : std::string()));
  CHECK(r.stopped < 0);
  CHECK(r.first_parted < 0);
  CHECK(test::within_relative(r.load_ratio, offset_reference, 0.03));  // the open tank's tolerance (above)
}

}  // namespace

TEST_SUITE("verification.fluid") {

// A known limitation of the default settings (docs/validation/fsi.md, open problems: water under
// a long structure): the water parts from the lid within about 0.1 s. What floating ice needs: the
// lid's mean load within the open tank's 3 % of hydrostatic (above; the reference is taken at the
// wall row's own height) and no lid particle at the free surface. Marked should_fail: it passes
// the suite while the limitation stands, and fails it once the defaults hold the water, to be
// turned into a plain test. The settings for water under a structure hold it (below).
TEST_CASE("verification.fluid: water under a lid stays hydrostatic (known limitation)" * doctest::should_fail()) {
  const auto r = water_under_lid(1.5, 0.01, 0.05, 0.3, 0.3, 2e-3, WallCondition::wall_rows);
  MESSAGE("water under a 1.5 m lid, l0 = 10 mm: mean lid load over 0.05-0.3 s / hydrostatic = " << r.load_ratio
          << ", steps with a lid particle at the free surface: " << r.steps_parted << " of " << r.steps);
  CHECK(test::within_relative(r.load_ratio, 1.0, 0.03));
  CHECK(r.steps_parted == 0);
}

TEST_CASE("verification.fluid: hydrostatic tank 2D") {
  // Tolerance 3 % of rho g H: the analytic pressure, with room for the known error sources. P = 0
  // is imposed on the surface particles, half a spacing below the true surface (l0 / (2 H) = 1.25 %
  // here), and the time average leaves some pressure noise. Measured 0.58 % (docs/validation/fluid.md).
  run_hydrostatic<2>(0.2, 0.2, 0.005, 1.0, 0.5, 5e-4);
}

TEST_CASE("verification.fluid: hydrostatic tank 2D with Neumann walls") {
  // The same case and tolerances with WallCondition::neumann.
  run_hydrostatic<2>(0.2, 0.2, 0.005, 1.0, 0.5, 5e-4, WallCondition::neumann);
}

// With WallCondition::neumann the water stays on the lid over the same window (no lid particle at
// the free surface; the default walls: 96 of 126 steps). The mean load is reported, not asserted:
// it is not within 3 %. The run goes on to 0.6 s to report when and where the water parts from
// the lid as a flow grows (docs/validation/fsi.md, open problems).
TEST_CASE("verification.fluid: water under a lid with Neumann walls: the water stays on the lid") {
  const auto r = water_under_lid(1.5, 0.01, 0.05, 0.3, 0.6, 2e-3, WallCondition::neumann);
  MESSAGE("Neumann walls: water under a 1.5 m lid, l0 = 10 mm: mean lid load over 0.05-0.3 s / hydrostatic = "
          << r.load_ratio << ", steps with a lid particle at the free surface: " << r.steps_parted << " of " << r.steps
          << "; over 0-0.6 s: first parting at t = " << r.first_parted << " s, lid particles at the free surface "
          << "from x = " << r.first_parted_from << " to " << r.first_parted_to
          << " m (closed end at 0), fastest fluid " << r.fastest << " m/s");
  CHECK(r.stopped < 0);
  CHECK(r.steps_parted == 0);
}

// The settings for water under a structure (docs/validation/fluid.md, "Water under a
// structure"): Neumann walls, CentroidDeviationSurface and the full density term. The open tank,
// same case and tolerances.
TEST_CASE("verification.fluid: hydrostatic tank 2D with the settings for water under a structure") {
  run_hydrostatic<2, WaterUnderStructure<2>>(0.2, 0.2, 0.005, 1.0, 0.5, 5e-4, WallCondition::neumann, false);
}

// The same settings under the lid, run to 2 s. The reference load takes P = 0 where the solver
// puts it, on the open water's surface particles half a spacing below the surface, so
// rho g (level - l0/2 - y) at the lid's wall row (0.923 of the plain hydrostatic load here); the
// tolerance is the open tank's 3 % (above). No lid particle may be at the free surface at any step.
TEST_CASE("verification.fluid: water under a lid with the settings for water under a structure") {
  check_water_under_lid_under_structure(1.5);
}

}  // TEST_SUITE

TEST_SUITE("validation.fluid") {

// Over a minute on 2 cores, so with the long runs; the 3D fluid step stays in the default suite
// through the coarse 3D dam break (dam_break.cpp).
TEST_CASE("validation.fluid: hydrostatic tank 3D") {
  // The 2D tank's tolerances; 30 layers deep so that the surface offset l0 / (2 H) is 1.7 %
  // (measured 2.0 %).
  run_hydrostatic<3>(0.08, 0.24, 0.008, 1.0, 0.5, 1e-3);
}

// Known limitations (docs/validation/fluid.md, "Water under a structure"): with the same
// settings the water does not hold under a lid twice as long, nor under the same lid at half the
// spacing. The load oscillates about hydrostatic with a growing amplitude, water comes over the
// lid's far end, and the run may stop before 2 s: each of these is the limitation. The floating
// beam of scenes::FloatingIceBeam at h = 80 mm and l0 = 10 mm needs 5 / lambda = 5.06 m of lid.
// Marked should_fail: they pass while the limitation stands and fail once the water holds, to be
// turned into plain tests.
TEST_CASE("validation.fluid: water under a 3 m lid with the settings for water under a structure (known limitation)" *
          doctest::should_fail()) {
  check_water_under_lid_under_structure(3.0);
}

// The 1.5 m lid of the default suite's case held over 10 s instead of 2 s: a known limitation
// (docs/validation/fluid.md, "Water under a structure"). The water stays on the lid, but its mean
// load falls more than 3 % below the reference: exactly that one check is expected to fail while
// it stands.
TEST_CASE("validation.fluid: water under a 1.5 m lid with the settings for water under a structure for 10 s "
          "(known limitation)" * doctest::expected_failures(1)) {
  check_water_under_lid_under_structure(1.5, 0.01, 10.0);
}

TEST_CASE("validation.fluid: water under a 1.5 m lid at l0 = 5 mm with the settings for water under a structure "
          "(known limitation)" * doctest::should_fail()) {
  check_water_under_lid_under_structure(1.5, 0.005);
}

// The same two lids, and the floating beam's 5.06 m at h = 80 mm, with the pressure gradient
// taken about each particle's own pressure (GradientReference::own_value) in place of the
// neighbours' minimum: the same checks as the 1.5 m lid in the default suite. At l0 = 5 mm the
// water holds (the run does not stop, no lid particle at P = 0) but the load is 5 % above the
// reference: exactly that one check is expected to fail while it stands.
TEST_CASE("validation.fluid: water under a 3 m lid with the settings and the own-value gradient") {
  check_water_under_lid_under_structure<WaterUnderLongStructure<2>>(3.0);
}

TEST_CASE("validation.fluid: water under a 5.06 m lid with the settings and the own-value gradient") {
  check_water_under_lid_under_structure<WaterUnderLongStructure<2>>(5.06);
}

// The 5.06 m lid held over 10 s instead of 2 s: a known limitation (docs/validation/fsi.md, open
// problems). The open water beyond the lid's far end sloshes with a growing amplitude, the lid's
// load climbs above hydrostatic, and the water under the lid's far corner bursts after about 4 s.
// A floating beam loaded slowly enough to be quasi-static needs tens of seconds. Marked
// should_fail, to be turned into a plain test once the water holds.
TEST_CASE("validation.fluid: water under a 5.06 m lid with the settings and the own-value gradient for 10 s "
          "(known limitation)" * doctest::should_fail()) {
  check_water_under_lid_under_structure<WaterUnderLongStructure<2>>(5.06, 0.01, 10.0);
}

TEST_CASE("validation.fluid: water under a 1.5 m lid at l0 = 5 mm with the settings and the own-value gradient "
          "(known limitation)" * doctest::expected_failures(1)) {
  check_water_under_lid_under_structure<WaterUnderLongStructure<2>>(1.5, 0.005);
}

// What the own-value gradient costs in the open tank (docs/validation/fluid.md): the pressure
// profile holds, the column height does not (same case and tolerances as above): exactly that
// one check is expected to fail while it stands.
TEST_CASE("validation.fluid: hydrostatic tank 2D with the settings and the own-value gradient (known limitation)" *
          doctest::expected_failures(1)) {
  run_hydrostatic<2, WaterUnderLongStructure<2>>(0.2, 0.2, 0.005, 1.0, 0.5, 5e-4, WallCondition::neumann, false);
}

}  // TEST_SUITE
