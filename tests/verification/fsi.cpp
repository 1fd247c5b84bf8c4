// SPDX-License-Identifier: BSD-3-Clause
// Verification of FsiCoupler (issue 6): the hydrostatic water column on a clamped elastic plate
// (Fourey et al. 2017; ../shared/validation-data/fsi_hydrostatic_plate_fourey2017_analytic.csv),
// the force balance, and where each coupling scheme is stable.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "mpsfsi/fluid/fluid_solver.hpp"
#include "mpsfsi/fsi/fsi_coupler.hpp"
#include "mpsfsi/scenes/hydrostatic_plate.hpp"
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
                                  double window) {
  std::vector<std::size_t> clamped;
  std::size_t middle = 0;
  ElasticSolver<2> plate(scene.plate_particles(l0, clamped, middle), plate_parameters(scene, l0));
  for (auto i : clamped) plate.clamp(i);
  FluidParameters<2> fp;
  fp.l0 = l0;
  fp.dt = dt;
  FsiCoupler<FluidSolver<2>, ElasticSolver<2>, Scheme> coupler(scene.fluid_particles(l0), fp, std::move(plate));
  const double y0 = coupler.solid().particles().positions()[middle][1];
  const double weight = water_weight(scene);
  HydrostaticResult r;
  int samples = 0;
  try {
    while (coupler.time() < t_end - 1e-12) {
      coupler.step();
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
  const double q = scene.fluid_density * scene.gravity * scene.water_height;
  const auto& x = plate.particles().positions();
  for (std::size_t i = 0; i < x.size(); ++i)
    if (x[i][1] > -l0 && x[i][0] > 0 && x[i][0] < scene.span) plate.external_force()[i] = Vec<2>(0, -q * l0);
  const double y0 = x[middle][1];
  plate.advance_to(t_end);
  return y0 - plate.particles().positions()[middle][1];
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
  // Issue 6, verification 2: the fluid's total force on the plate is its weight within 2 %.
  CHECK(test::within_relative(r.load, weight, 0.02));
  // The coupled deflection is the plate's own response to that load: within 2 % (the load's
  // tolerance; the deflection is linear in it) of the plate alone under rho g H.
  CHECK(test::within_relative(r.deflection, alone, 0.02));
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
}

}  // TEST_SUITE
