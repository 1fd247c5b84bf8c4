// SPDX-License-Identifier: BSD-3-Clause
// Verification of FsiCoupler: the hydrostatic water column on a clamped elastic plate (Fourey et
// al. 2017; analytic deflection in scenes::HydrostaticPlate), the force balance, and where each
// coupling scheme is stable.
#include <doctest/doctest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <vector>

#include "floating_ice_beam/beam_in_water.hpp"
#include "mpsfsi/fluid/fluid_solver.hpp"
#include "mpsfsi/fluid/water_under_structure.hpp"
#include "mpsfsi/fsi/fsi_coupler.hpp"
#include "mpsfsi/scenes/elastic_gate.hpp"
#include "mpsfsi/scenes/floating_ice_beam.hpp"
#include "mpsfsi/scenes/hydrostatic_plate.hpp"
#include "mpsfsi/scenes/solid_block.hpp"
#include "mpsfsi/scenes/tank.hpp"
#include "mpsfsi/solid/elastic_solver.hpp"
#include "support/tolerance.hpp"

using namespace mpsfsi;

namespace {

// Velocity damping of the plate (1/s): the test asks for the static equilibrium, so the
// coupled plate-water oscillation set off by the sudden load is damped out (its period is
// about 16 ms; 300/s damps it within about 50 ms). The solid-only reference uses the same.
constexpr double plate_damping = 300;

struct HydrostaticResult {
  double deflection = 0;  // mid-span, positive down, averaged over the window
  double load = 0;        // total vertical fluid force on the plate (N/m), positive down, averaged
  double max_load_deviation = 0;  // max |load / W - 1| over the window
  double fluid_solves_per_step = 0;  // coupling iterations (one fluid solve each), mean over the run
  bool blew_up = false;
};

SolidParameters<2> plate_parameters(const scenes::HydrostaticPlate& scene, double l0) {
  SolidParameters<2> p;
  p.l0 = l0;
  scene.set_material(p);
  p.plane_model = PlaneModel::plane_strain;  // the analytic D = E e^3 / (12 (1 - nu^2))
  p.gravity.setZero();                       // the water-only case of the reference (6.43e-5 m)
  p.damping = plate_damping;
  return p;
}

double water_weight(const scenes::HydrostaticPlate& s) { return s.fluid_density * s.gravity * s.water_height * s.span; }

template <class Scheme>
HydrostaticResult run_hydrostatic(const scenes::HydrostaticPlate& scene, double l0, double dt, double t_end,
                                  double window, const CouplingParameters& cp = CouplingParameters()) {
  std::vector<std::size_t> clamped;
  std::size_t middle = 0;
  ElasticSolver<2> plate(scene.plate_particles(l0, clamped, middle), plate_parameters(scene, l0));
  for (auto i : clamped) plate.clamp(i);
  FluidParameters<2> fp;
  fp.l0 = l0;
  fp.dt = dt;
  FsiCoupler<FluidSolver<2>, ElasticSolver<2>, Scheme> coupler(scene.fluid_particles(l0), fp, std::move(plate), cp);
  const double y0 = coupler.solid().particles().positions()[middle][1];
  const double weight = water_weight(scene);
  HydrostaticResult r;
  int samples = 0;
  int steps = 0, solves = 0;
  try {
    while (coupler.time() < t_end - 1e-12) {
      coupler.step();
      ++steps;
      solves += coupler.last_iterations();
      r.fluid_solves_per_step = double(solves) / steps;
      if (coupler.time() < t_end - window - 1e-12) continue;
      const double load = -coupler.total_interface_force()[1];
      r.deflection += y0 - coupler.solid().particles().positions()[middle][1];
      r.load += load;
      r.max_load_deviation = std::max(r.max_load_deviation, std::abs(load / weight - 1));
      ++samples;
    }
  } catch (const SimulationError& e) {
    std::printf("  (%s: %s)\n", Scheme::name, e.what());
    r.blew_up = true;
    return r;
  }
  r.deflection /= samples;
  r.load /= samples;
  std::printf("  %s, rho_s/rho_f = %.1f: fluid %.1f s, structure %.1f s\n", Scheme::name,
              scene.density / scene.fluid_density, coupler.fluid_seconds(), coupler.solid_seconds());
  return r;
}

// The same plate alone under the analytic hydrostatic load q = rho g H on its wetted top surface:
// what the coupled run must reproduce if the coupling is right, whatever the plate's own
// discretisation error.
double plate_alone(const scenes::HydrostaticPlate& scene, double l0, double t_end) {
  std::vector<std::size_t> clamped;
  std::size_t middle = 0;
  ElasticSolver<2> plate(scene.plate_particles(l0, clamped, middle), plate_parameters(scene, l0));
  for (auto i : clamped) plate.clamp(i);
  scene.apply_water_load(plate, l0);
  const double y0 = plate.particles().positions()[middle][1];
  plate.advance_to(t_end);
  return y0 - plate.particles().positions()[middle][1];
}

// The floating beam of scenes::FloatingIceBeam (h = 80 mm, l0 = 10 mm: 5.06 m of ice on 0.25 m of
// water), its loaded end on a roller at mid-thickness against the tank wall (roller_particle), no
// load, coupled by `Scheme` with the settings for water under a structure (docs/theory.md, section
// 2.9), the own-value pressure gradient and negative pressures kept, at a fixed step `dt`, with or
// without eq 10's interface acceleration in the fluid's predictor (docs/theory.md, section 4.4).
// The ice's inertia is scaled by `inertia_scale` and its gravity by the inverse, so its weight
// stays. Reports the vertical fluid force on the ice against its weight over [window_start, t_end]
// and the fluid solves per step.
struct FloatingBeamResult {
  double max_load_deviation = 0;     // max |F / W - 1| over the window's steps
  double max_block_deviation = 0;    // max |F / W - 1| of the means over 0.05 s blocks of the window
  double mean_load = 0;              // mean F / W over the window
  double fluid_solves_per_step = 0;  // mean over the run
  int most_fluid_solves = 0;         // in one step
  double far_end_sink = 0;           // the far end's bottom corner: how far it moved down by t_end, m
  bool blew_up = false;
};

template <class Scheme = ExplicitPartitioned>
FloatingBeamResult floating_beam(double inertia_scale, double dt, double t_end, double window_start,
                                 bool interface_acceleration = true) {
  scenes::FloatingIceBeam scene;
  scene.thickness = 0.08;
  const double l0 = 0.01;
  std::vector<std::size_t> end_column;
  auto beam = scene.beam_particles(l0, end_column);
  const auto roller = scene.roller_particle(beam, end_column, l0);
  ElasticSolver<2> ice(std::move(beam), floating_ice::floating_ice_parameters(scene, l0, inertia_scale));
  ice.support(roller, Vec<2>(1, 0));
  const auto fp = floating_ice::water_under_ice_parameters(l0, dt);
  CouplingParameters cp;
  cp.interface_acceleration = interface_acceleration;
  FsiCoupler<FluidSolver<2, WaterUnderLongStructure<2>>, ElasticSolver<2>, Scheme> coupler(
      scene.fluid_particles(l0), fp, std::move(ice), cp);
  const double weight = scene.ice_density * scene.gravity * scene.thickness * scene.beam_length_for(l0);
  const auto& ice_x = coupler.solid().particles().positions();
  const double far_end = scene.beam_length_for(l0) - l0, bottom_row = scene.beam_bottom(l0) + l0;
  const std::size_t far_corner = scenes::select(coupler.solid().particles(), [&](const Vec<2>& x) {
    return x[0] > far_end && x[1] < bottom_row;
  })[0];
  const double far_corner_y0 = ice_x[far_corner][1];
  FloatingBeamResult r;
  int samples = 0, block_samples = 0;
  long long solves = 0, steps = 0;
  double block_sum = 0;
  const int block = static_cast<int>(std::lround(0.05 / fp.dt));
  try {
    while (coupler.time() < t_end - 1e-12) {
      coupler.step();
      solves += coupler.last_iterations();
      ++steps;
      r.most_fluid_solves = std::max(r.most_fluid_solves, coupler.last_iterations());
      r.fluid_solves_per_step = double(solves) / double(steps);
      r.far_end_sink = far_corner_y0 - ice_x[far_corner][1];
      if (coupler.time() < window_start - 1e-12) continue;
      const double load = coupler.total_interface_force()[1] / weight;
      r.max_load_deviation = std::max(r.max_load_deviation, std::abs(load - 1));
      r.mean_load += load;
      ++samples;
      block_sum += load;
      if (++block_samples == block) {
        r.max_block_deviation = std::max(r.max_block_deviation, std::abs(block_sum / block - 1));
        block_sum = 0;
        block_samples = 0;
      }
    }
  } catch (const SimulationError& e) {
    std::printf("  (%s, inertia x %g, dt = %g s, interface acceleration %s: %s)\n", Scheme::name, inertia_scale, dt,
                interface_acceleration ? "on" : "off", e.what());
    r.blew_up = true;
    return r;
  }
  r.mean_load /= samples;
  return r;
}

// The floating beam's scene of the end-load study (floating_ice::water_scene: h = 80 mm, 875
// kg/m3) shortened to 0.8 m of ice on 0.12 m of water with 0.12 m of open water, h/l0 = 4, its
// run's settings (IQN-ILS, the linear fit, inertia x16, damped), unloaded, to t_end: the 2D beam,
// or the 3D strip three thicknesses wide across its channel.
floating_ice::WaterRunResult short_floating_ice(int dim, double t_end) {
  auto scene = floating_ice::water_scene();
  scene.beam_length = 0.8;
  scene.water_depth = 0.12;
  scene.open_water = 0.12;
  scene.width = 3 * scene.thickness;
  const auto settings = floating_ice::water_settings(scene, scene.thickness / 4, t_end);
  const floating_ice::EndLoad no_load;
  return dim == 3 ? floating_ice::run_in_water<ElasticSolver<3>>(scene, settings, no_load)
                  : floating_ice::run_in_water<ElasticSolver<2>>(scene, settings, no_load);
}

}  // namespace

TEST_SUITE("verification.fsi") {

TEST_CASE("hydrostatic plate: force balance and deflection") {
  // l0 = 0.0125 m: the plate is 4 particles thick. Sub-iterated coupling: the explicit scheme
  // is unstable at this density ratio (next test).
  scenes::HydrostaticPlate scene;
  const double l0 = 0.0125, t_end = 0.08, window = 0.03;
  const auto r = run_hydrostatic<SubIterated>(scene, l0, 1e-3, t_end, window);
  REQUIRE(!r.blew_up);
  const double weight = water_weight(scene);
  const double alone = plate_alone(scene, l0, t_end);
  const double analytic = scene.deflection(false);
  std::printf("hydrostatic plate, l0 = %.4f m: load %.4f W (max deviation %.4f), deflection %.4e m; plate alone "
              "under rho g H %.4e m (coupled %+.2f %%); analytic %.4e m (coupled %+.1f %%, plate alone %+.1f %%)\n",
              l0, r.load / weight, r.max_load_deviation, r.deflection, alone, 100 * (r.deflection / alone - 1),
              analytic, 100 * (r.deflection / analytic - 1), 100 * (alone / analytic - 1));
  // Force balance: the fluid's total force on the plate is the column's weight, within 2 %
  // (measured 1.0047 W; without the partial-wetting correction of eq 18 it is 1.04 W, which this
  // bound rejects; docs/validation/fsi.md).
  CHECK(test::within_relative(r.load, weight, 0.02));
  // The coupled deflection is the plate's own response to that load: within 2 % (the load's
  // tolerance; the deflection is linear in it) of the plate alone under rho g H.
  CHECK(test::within_relative(r.deflection, alone, 0.02));
  // The same with eq 18's pressure as the linear fit of the water's pressure at the interface
  // point (docs/theory.md, section 4.3), against the same two bounds: measured 0.9993 W and
  // +0.00 % against the plate alone.
  CouplingParameters fit;
  fit.interface_pressure = InterfacePressure::linear_fit;
  const auto f = run_hydrostatic<SubIterated>(scene, l0, 1e-3, t_end, window, fit);
  REQUIRE(!f.blew_up);
  std::printf("  with the linear fit: load %.4f W (max deviation %.4f), deflection %.4e m (plate alone %+.2f %%)\n",
              f.load / weight, f.max_load_deviation, f.deflection, 100 * (f.deflection / alone - 1));
  CHECK(test::within_relative(f.load, weight, 0.02));
  CHECK(test::within_relative(f.deflection, alone, 0.02));
}

TEST_CASE("coupling schemes: where each is stable against the structure-to-fluid density ratio") {
  // The hydrostatic plate over 30 ms, judged by the load on the plate over the last 10 ms: stable
  // when it stays within 10 % of the water's weight, unstable when it leaves 50 % (or the run
  // blows up). Measured: explicit unstable at rho_s/rho_f = 2.7 and 5.4, oscillating +-7 % at
  // 10.8, stable at 27 and 270; sub-iterated stable at 1.0 and 2.7.
  const double l0 = 0.0125, dt = 1e-3, t_end = 0.03, window = 0.01;
  scenes::HydrostaticPlate scene;
  auto with_density = [&](double rho) {
    auto s = scene;
    s.density = rho;
    return s;
  };
  const auto explicit_light = run_hydrostatic<ExplicitPartitioned>(with_density(2700), l0, dt, t_end, window);
  CHECK((explicit_light.blew_up || explicit_light.max_load_deviation > 0.5));
  const auto explicit_heavy = run_hydrostatic<ExplicitPartitioned>(with_density(27000), l0, dt, t_end, window);
  CHECK(!explicit_heavy.blew_up);
  CHECK(explicit_heavy.max_load_deviation < 0.1);
  const auto iterated_light = run_hydrostatic<SubIterated>(with_density(1000), l0, dt, t_end, window);
  CHECK(!iterated_light.blew_up);
  CHECK(iterated_light.max_load_deviation < 0.1);
  std::printf("load deviation over the last 10 ms: explicit 2.7: %s%.3f, explicit 27: %.3f, sub-iterated 1.0: %.3f\n",
              explicit_light.blew_up ? "blew up, " : "", explicit_light.max_load_deviation,
              explicit_heavy.max_load_deviation, iterated_light.max_load_deviation);
  // The cost of the strongly coupled schemes: fluid solves per step at rho_s/rho_f = 1 and 2.7.
  // Aitken must be stable at both. IQN-ILS is run and reported, not asserted: it does not converge
  // here (docs/validation/fsi.md, open problems).
  const auto iterated_27 = run_hydrostatic<SubIterated>(with_density(2700), l0, dt, t_end, window);
  CHECK(!iterated_27.blew_up);
  CHECK(iterated_27.max_load_deviation < 0.1);
  const auto quasi_newton_1 = run_hydrostatic<InterfaceQuasiNewton>(with_density(1000), l0, dt, t_end, window);
  const auto quasi_newton_27 = run_hydrostatic<InterfaceQuasiNewton>(with_density(2700), l0, dt, t_end, window);
  std::printf("sub-iterated 2.7: load deviation %.3f; fluid solves per step, rho_s/rho_f = 1.0 / 2.7: Aitken "
              "%.2f / %.2f; IQN-ILS %s / %s\n",
              iterated_27.max_load_deviation, iterated_light.fluid_solves_per_step, iterated_27.fluid_solves_per_step,
              quasi_newton_1.blew_up ? "not converged" : "converged", quasi_newton_27.blew_up ? "not converged" : "converged");
}

TEST_CASE("floating beam: the explicit scheme needs the ice's inertia scaled past the water's added mass") {
  // The water squeezed from under the 5.06 m beam through 0.25 m of depth adds a mass of order
  // rho_w L^2 / d = 1e5 kg per m^2 of beam to its slowest motion, against the ice's
  // rho_i h = 73 kg/m^2 (docs/validation/fsi.md, open problems). The explicit scheme is stable
  // only while the structure outweighs what it carries, so it must fail at 1,000 times the ice's
  // inertia and hold at 5,000. Measured: it fails at 2,000 and holds at 3,000. Unstable: a
  // failed step or a step's load 50 % off the weight (as in the test above). Stable: no failed
  // step and every 0.05 s mean of the load within 5 % of the weight. Single steps scatter by up
  // to 15 % (measured at 5,000), so the blocks, not the steps, are judged. The
  // bounds separate stable from unstable; they are not accuracy bounds.
  const auto light = floating_beam(1000, 2e-3, 0.2, 0.0);
  CHECK((light.blew_up || light.max_load_deviation > 0.5));
  const auto heavy = floating_beam(5000, 2e-3, 0.6, 0.1);
  CHECK(!heavy.blew_up);
  CHECK(heavy.max_block_deviation < 0.05);
  std::printf("floating beam, explicit: inertia x 1000: %s%.3g; x 5000: over 0.1-0.6 s largest |F/W - 1| of a step "
              "%.4f, of a 0.05 s mean %.4f, mean F/W %.4f\n",
              light.blew_up ? "blew up, " : "largest |F/W - 1| ", light.max_load_deviation, heavy.max_load_deviation,
              heavy.max_block_deviation, heavy.mean_load);
}

TEST_CASE("crack entry: a crack opened under water becomes surface and the water flows into it") {
  // An ice block 0.1 m x 0.04 m on the floor of a tank 0.3 m wide, under 0.1 m of water, is
  // cut through along x = 0.15 m (impose_crack: bonds only, the faces still touch), and its two
  // halves are then moved apart at 0.05 m/s each (prescribed velocities: the structure is
  // kinematic, so what is tested is the coupler, not the solid). After 0.2 s the crack is 0.02 m
  // (4 l0) wide between its faces' outer particles.
  const double l0 = 0.005, speed = 0.05, t_end = 0.2, t_settle = 0.5, window = 0.1, crack_x = 0.15, top = 0.04;
  ParticleSet<2> tank;
  scenes::add_block<2, double>(tank, Vec<2>(0, 0), Vec<2>(0.1, 0.1), l0, ParticleKind::fluid);
  scenes::add_block<2, double>(tank, Vec<2>(0.2, 0), Vec<2>(0.3, 0.1), l0, ParticleKind::fluid);
  scenes::add_block<2, double>(tank, Vec<2>(0.1, top), Vec<2>(0.2, 0.1), l0, ParticleKind::fluid);
  scenes::add_tank<2, double>(tank, Vec<2>(0.3, 0.15), l0);
  SolidParameters<2> sp;
  sp.l0 = l0;
  sp.density = 917;
  sp.youngs_modulus = 1e8;
  sp.poisson_ratio = 0.3;
  ElasticSolver<2> block(scenes::material_block<2>(Vec<2>(0.1, 0), Vec<2>(0.2, top), l0), sp);
  const VecArray<2> x0 = block.particles().positions();  // a copy: the block moves into the coupler
  std::size_t crack_cuts = 0;
  for (std::size_t i = 0; i < x0.size(); ++i)
    if (std::abs(x0[i][0] - (crack_x + l0 / 2)) < 1e-9) crack_cuts += block.impose_crack(i, Vec<2>(1, 0));
  REQUIRE(crack_cuts > 0);
  for (std::size_t i = 0; i < x0.size(); ++i) block.prescribe_velocity(i, Vec<2>(x0[i][0] < crack_x ? -speed : speed, 0));
  FluidParameters<2> fp;
  fp.l0 = l0;
  FsiCoupler<FluidSolver<2>, ElasticSolver<2>> coupler(std::move(tank), fp, std::move(block));
  coupler.advance_to(t_end);
  const double opened = coupler.time();
  for (std::size_t i = 0; i < coupler.solid().particles().size(); ++i) coupler.solid().clamp(i);  // the crack stays open
  // Settle, then average the pressure of the water in the crack over the last 0.1 s against
  // the hydrostatic rho g (H - y), H the level the water's volume gives (the crack took
  // 0.02 m x 0.04 m of it from a tank 0.3 m wide). Reported, not asserted: the ~33 particles'
  // MPS pressure fluctuates so much that this average came out 0.9999 in one build and 1.032 in
  // another (the same code with and without FMA: round-off alone), and over 0.3 s after
  // settling to 0.8 s 1.08 +- 0.08 (standard error); in the FMA build water was even pushed
  // out of the crack between 0.5 and 0.8 s (docs/validation/fsi.md, open problems). The standard
  // error of the mean, from 10 batches, is printed with it.
  const double level = 0.1 - (2 * speed * opened) * top / 0.3;
  constexpr int batches = 10;
  double pressure_sum = 0, hydrostatic_sum = 0;
  std::array<double, batches> batch_p{}, batch_h{};
  while (coupler.time() < t_settle) {
    coupler.step();
    if (coupler.time() < t_settle - window) continue;
    const int batch = std::min(batches - 1, static_cast<int>((coupler.time() - (t_settle - window)) / window * batches));
    const auto& fluid = coupler.fluid().particles();
    for (std::size_t i = 0; i < coupler.structure_offset(); ++i) {
      const Vec<2> p = fluid.positions()[i];
      if (fluid.kinds()[i] != ParticleKind::fluid || std::abs(p[0] - crack_x) > 1.5 * l0 || p[1] > top) continue;
      batch_p[static_cast<std::size_t>(batch)] += coupler.fluid().pressure()[i];
      batch_h[static_cast<std::size_t>(batch)] += 1000 * 9.81 * (level - p[1]);
    }
  }
  double mean_ratio = 0, spread = 0;
  for (int k = 0; k < batches; ++k) {
    pressure_sum += batch_p[static_cast<std::size_t>(k)];
    hydrostatic_sum += batch_h[static_cast<std::size_t>(k)];
    mean_ratio += batch_p[static_cast<std::size_t>(k)] / batch_h[static_cast<std::size_t>(k)] / batches;
  }
  for (int k = 0; k < batches; ++k)
    spread += std::pow(batch_p[static_cast<std::size_t>(k)] / batch_h[static_cast<std::size_t>(k)] - mean_ratio, 2);
  const double standard_error = std::sqrt(spread / (batches - 1) / batches);

  // The faces: surface (walls in the PPE) with normals into the crack, below the top corners.
  const auto& xs = coupler.solid().particles().positions();
  const auto& x_ref = coupler.solid().reference_positions();
  double left_face = -1, right_face = 1;
  for (std::size_t i = 0; i < xs.size(); ++i) {
    const bool left = std::abs(x_ref[i][0] - (crack_x - l0 / 2)) < 1e-9, right = std::abs(x_ref[i][0] - (crack_x + l0 / 2)) < 1e-9;
    if (!left && !right) continue;
    CHECK(coupler.on_surface()[i] == 1);
    if (x_ref[i][1] > l0 && x_ref[i][1] < top - 2 * l0)
      CHECK(coupler.normals()[i].dot(Vec<2>(left ? 1 : -1, 0)) > 0.95);
    (left ? left_face : right_face) = xs[i][0];
  }
  CHECK(right_face - left_face == doctest::Approx(l0 + 2 * speed * opened).epsilon(1e-9));

  // The water in the crack: fluid particles between the faces and below the block's top. On the
  // lattice the gap holds (width / l0 - 1) columns of (top / l0) rows; the count is held to 80 %
  // of that (free-surface particles keep about l0/2 more from a wall than interior ones, and the
  // water reaching the bottom last arrives within the last ~0.05 s).
  const auto& fluid = coupler.fluid().particles();
  int inside = 0;
  for (std::size_t i = 0; i < coupler.structure_offset(); ++i) {
    const Vec<2> p = fluid.positions()[i];
    inside += fluid.kinds()[i] == ParticleKind::fluid && p[0] > left_face + l0 / 2 && p[0] < right_face - l0 / 2 && p[1] < top;
  }
  const double capacity = ((right_face - left_face) / l0 - 1) * (top / l0);
  MESSAGE("crack " << (right_face - left_face) / l0 << " l0 wide: " << inside << " fluid particles inside (lattice capacity "
                   << capacity << "); its water's pressure over the last 0.1 s, averaged: "
                   << pressure_sum / hydrostatic_sum << " of hydrostatic (standard error of the mean "
                   << standard_error << "); enclosed-region steps "
                   << coupler.fluid().steps_with_enclosed_regions());
  CHECK(inside >= 0.8 * capacity);
  CHECK(hydrostatic_sum > 0);  // there was water in the crack during the window
}

// The elastic gate's surge reaches the low end wall at about 0.2 s and runs up it. Its fastest
// fluid particle must stay below twice Ritter's front speed 2 sqrt(g H0) (the fastest speed of the
// ideal dam break, H0 the column height; analytic). The run-up at the wall turns the surge's
// momentum upwards at about the front speed, so the factor 2 is a margin for it; a particle
// kicked off a wall by a spurious wall pressure (docs/validation/fluid.md, the collision
// distance) runs at several times the front speed and sets the time step.
TEST_CASE("elastic gate: the surge at the end wall stays below twice the dam-break front speed") {
  const scenes::ElasticGate scene;
  const double l0 = 0.0025, t_end = 0.25;
  std::vector<std::size_t> clamped;
  std::size_t tip = 0;
  SolidParameters<2> sp;
  sp.l0 = l0;
  scene.set_material(sp);
  sp.gravity = scene.gravity_vector<2>();
  ElasticSolver<2> gate(scene.gate_particles<2>(l0, clamped, tip), sp);
  for (auto i : clamped) gate.clamp(i);
  FluidParameters<2> fp;
  fp.l0 = l0;
  fp.gravity = scene.gravity_vector<2>();
  SubIterated scheme;
  scheme.tolerance = 1e-2;  // the example's
  FsiCoupler<FluidSolver<2>, ElasticSolver<2>, SubIterated> coupler(scene.fluid_particles<2>(l0), fp, std::move(gate),
                                                                   CouplingParameters{}, scheme);
  const double front_speed = 2 * std::sqrt(scene.gravity * scene.water_height);
  const double end_wall = scene.water_width + scene.floor_length;
  double fastest = 0, fastest_at = 0, smallest_dt = 1e300, reach = 0;
  while (coupler.time() < t_end - 1e-12) {
    coupler.step();
    smallest_dt = std::min(smallest_dt, coupler.fluid().last_dt());
    if (coupler.fluid().fastest_fluid_speed() > fastest) {
      fastest = coupler.fluid().fastest_fluid_speed();
      fastest_at = coupler.time();
    }
  }
  const auto& fluid = coupler.fluid().particles();
  for (std::size_t i = 0; i < coupler.structure_offset(); ++i)
    if (fluid.kinds()[i] == ParticleKind::fluid) reach = std::max(reach, fluid.positions()[i][0]);
  MESSAGE("fastest fluid particle " << fastest << " m/s at t = " << fastest_at << " s (front speed 2 sqrt(g H0) = "
                                    << front_speed << " m/s); smallest time step " << smallest_dt
                                    << " s; furthest water at x = " << reach << " m (end wall at " << end_wall << " m)");
  CHECK(reach > end_wall - 2 * l0);  // the surge reached the end wall within the run
  CHECK(fastest < 2 * front_speed);
}

// The strip's channel is mirror symmetric about its mid-plane, z = width / 2, and so are the
// water, the ice and gravity (along -y, the scene's vertical): the strip cannot roll about its long
// axis or drift across the channel but by round-off. Measured over 0.25 s: the two sides' mean
// heights and the drift agree to 1e-12 m.
TEST_CASE("floating strip (3D): floats level in its channel") {
  const auto r = short_floating_ice(3, 0.25);
  std::printf("floating strip (3D), %zu ice and %zu water and tank particles, to 0.25 s: roll %.2e m, across the "
              "channel %.2e m, sinking %.3f mm, fluid solves per step %.2f, %.1f s\n",
              r.ice_particles, r.water_particles, r.roll, r.sideways, 1e3 * r.sinking, r.fluid_solves_per_step,
              r.wall_seconds);
  REQUIRE(!r.blew_up);
  CHECK(std::abs(r.roll) < 1e-9);
  CHECK(std::abs(r.sideways) < 1e-9);
}

}  // TEST_SUITE

// Long: the resolution study of the plate alone and the free floating beam at the ice's own
// inertia (label "validation", about 4 and 6 minutes on 2 cores).
TEST_SUITE("validation.fsi") {

TEST_CASE("floating beam: IQN-ILS holds the free beam at the ice's own inertia") {
  // The beam of the explicit-scheme test above, unscaled (rho_s/rho_f = 0.92), coupled by IQN-ILS.
  // At rest the water carries the ice's weight (Archimedes); the bound is the floating beam's
  // force-balance tolerance, 1 % (docs/validation/fsi.md), on every 0.05 s mean over 0.1-0.5 s.
  // Eq 10's interface acceleration is the structure's acceleration of the previous step, a lagged
  // term in an otherwise converged step: with it, a 2 ms step is unstable (IQN-ILS converges at
  // every step while the force drifts away from the weight, faster and faster, until a step does
  // not converge at 0.27 s) and 1 ms holds; without it, 2 ms holds. Measured: the 0.05 s means
  // within 0.02 %, 4.3 fluid solves a step, in both stable runs. Unstable is judged as in the
  // explicit-scheme test: a failed step or a step's load 50 % off the weight.
  const auto without = floating_beam<InterfaceQuasiNewton>(1, 2e-3, 0.5, 0.1, false);
  CHECK(!without.blew_up);
  CHECK(without.max_block_deviation < 0.01);
  const auto with = floating_beam<InterfaceQuasiNewton>(1, 2e-3, 0.3, 0.0, true);
  CHECK((with.blew_up || with.max_load_deviation > 0.5));
  const auto with_short_step = floating_beam<InterfaceQuasiNewton>(1, 1e-3, 0.5, 0.1, true);
  CHECK(!with_short_step.blew_up);
  CHECK(with_short_step.max_block_deviation < 0.01);
  auto report = [](const char* what, const FloatingBeamResult& r) {
    std::printf("floating beam, IQN-ILS, the ice's own inertia, %s: ", what);
    if (r.blew_up) {
      std::printf("failed\n");
      return;
    }
    std::printf("over 0.1 s to the end largest |F/W - 1| of a step %.4f, of a 0.05 s mean %.4f, mean F/W %.5f; "
                "fluid solves per step %.2f (at most %d); the far end's bottom corner %.2f mm lower at the end\n",
                r.max_load_deviation, r.max_block_deviation, r.mean_load, r.fluid_solves_per_step, r.most_fluid_solves,
                1e3 * r.far_end_sink);
  };
  report("dt = 2 ms, no interface acceleration", without);
  report("dt = 2 ms, interface acceleration", with);
  report("dt = 1 ms, interface acceleration", with_short_step);
}

// The 3D strip against the 2D beam, unloaded over 3 s: both float, the water carrying the ice's
// weight within the floating beam's force-balance tolerance, 1 % (docs/validation/fsi.md), on every
// 1 s mean. Measured: 3D -0.60 %, -0.18 %, -0.05 %; 2D +0.20 %, -0.01 %, -0.03 %. The strip settles
// 1.3 mm lower (the 2D beam 0.3 mm higher) from where both start, a draft 0.08 l0 deeper. Its
// mirror symmetry holds to round-off to 1 s; its sides differ by 2e-9 m at 1.5 s, 6e-6 m at 2 s
// and 1.7e-5 m at 3 s (reported, not asserted: the short run above checks the symmetry).
TEST_CASE("floating strip (3D): carries its weight as the 2D beam does") {
  const auto strip = short_floating_ice(3, 3), beam = short_floating_ice(2, 3);
  for (const auto* r : {&strip, &beam})
    std::printf("floating %s unloaded to 3 s: largest |F/W - 1| of a 1 s mean %.4f, sinking %.3f mm, roll %.2e m, "
                "across %.2e m, water on the ice %d, fluid solves per step %.2f (at most %d), %.0f s\n",
                r == &strip ? "strip (3D)" : "beam (2D)", r->run_balance_error, 1e3 * r->sinking, r->roll, r->sideways,
                r->water_on_ice, r->fluid_solves_per_step, r->most_fluid_solves, r->wall_seconds);
  REQUIRE(!strip.blew_up);
  REQUIRE(!beam.blew_up);
  CHECK(strip.run_balance_error < 0.01);
  CHECK(beam.run_balance_error < 0.01);
}

TEST_CASE("hydrostatic plate alone: the deflection converges to within 5 % of Euler-Bernoulli") {
  // The coupled deflection follows the plate alone under rho g H within 0.34 % at h/l0 = 4 (the
  // verification above), so what separates it from the analytic 6.43e-5 m is the plate's own
  // discretisation. Its error, measured at h/l0 = 4, 5, 8, 10, 16, 20 (docs/validation/fsi.md), fits
  //   e(n) = e_inf + b / n + c / n^2,  n = h / l0,
  // with c close to the midpoint rule's 1/n^2 deficit in the moment of inertia and b the
  // first-order surface and clamp error. Here the three finest affordable levels give e_inf by
  // that fit. The claim: the error falls with every refinement, and the converged plate lies
  // between 0 and 5 % above the analytic deflection: above, because the 2D plate has shear
  // deformation, which Euler-Bernoulli leaves out (Timoshenko's estimate is +3.6 % at L/h = 20);
  // the study's fit puts the limit at +2.8 % (n = 8-20) or +3.0 % (all six levels).
  scenes::HydrostaticPlate scene;
  const double analytic = scene.deflection(false);
  const std::array<double, 3> n{8, 10, 16};
  std::array<double, 3> e{};
  for (std::size_t k = 0; k < n.size(); ++k) {
    e[k] = plate_alone(scene, scene.thickness / n[k], 0.06) / analytic - 1;
    std::printf("plate alone, h/l0 = %.0f: %+.2f %% of the analytic deflection\n", n[k], 100 * e[k]);
  }
  CHECK(e[0] > e[1]);
  CHECK(e[1] > e[2]);
  // Solve the 3x3 system for (e_inf, b, c) by Cramer's rule.
  auto det3 = [](const std::array<std::array<double, 3>, 3>& m) {
    return m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
           m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
  };
  std::array<std::array<double, 3>, 3> m{}, m0{};
  for (std::size_t k = 0; k < 3; ++k) {
    m[k] = {1.0, 1 / n[k], 1 / (n[k] * n[k])};
    m0[k] = {e[k], 1 / n[k], 1 / (n[k] * n[k])};
  }
  const double converged = det3(m0) / det3(m);
  std::printf("extrapolated to h/l0 -> infinity: %+.2f %%\n", 100 * converged);
  CHECK(converged > 0);
  CHECK(converged < 0.05);
}

}  // TEST_SUITE
