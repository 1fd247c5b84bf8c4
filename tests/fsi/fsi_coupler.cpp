// SPDX-License-Identifier: BSD-3-Clause
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>

#include "mpsfsi/fluid/fluid_solver.hpp"
#include "mpsfsi/fsi/fsi_coupler.hpp"
#include "mpsfsi/scenes/elastic_gate.hpp"
#include "mpsfsi/scenes/hydrostatic_plate.hpp"
#include "mpsfsi/solid/elastic_solver.hpp"

using namespace mpsfsi;

namespace {

// A small water column on a clamped plate (the hydrostatic-plate scene scaled down).
struct SmallCase {
  scenes::HydrostaticPlate scene;
  double l0 = 0.01;
  std::vector<std::size_t> clamped;
  std::size_t middle = 0;
  SmallCase() {
    scene.span = 0.1;
    scene.water_height = 0.05;
    scene.thickness = 0.02;
    scene.youngs_modulus = 1e8;
  }
  ElasticSolver<2> solid(double l0_solid) {
    SolidParameters<2> p;
    p.l0 = l0_solid;
    scene.set_material(p);
    ElasticSolver<2> s(scene.plate_particles(l0_solid, clamped, middle), p);
    for (auto i : clamped) s.clamp(i);
    return s;
  }
  FluidParameters<2> fluid_parameters() const {
    FluidParameters<2> p;
    p.l0 = l0;
    p.dt = 1e-3;
    return p;
  }
};

}  // namespace

TEST_SUITE("fsi") {

TEST_CASE("fsi.coupler: different particle spacings are refused with a clear error") {
  SmallCase c;
  CHECK_THROWS_WITH_AS((FsiCoupler<FluidSolver<2>, ElasticSolver<2>>(c.scene.fluid_particles(c.l0), c.fluid_parameters(),
                                                                     c.solid(c.l0 / 2))),
                       doctest::Contains("different particle spacings"), InvalidInput);
  CouplingParameters bad;
  bad.surface_threshold = 2;
  CHECK_THROWS_WITH_AS((FsiCoupler<FluidSolver<2>, ElasticSolver<2>>(c.scene.fluid_particles(c.l0), c.fluid_parameters(),
                                                                     c.solid(c.l0), bad)),
                       doctest::Contains("surface_threshold"), InvalidInput);
}

TEST_CASE("fsi.coupler: the structure joins the fluid as wall on its surface and dummy inside") {
  SmallCase c;
  auto fluid_set = c.scene.fluid_particles(c.l0);
  const std::size_t n_fluid_set = fluid_set.size();
  FsiCoupler<FluidSolver<2>, ElasticSolver<2>> coupler(std::move(fluid_set), c.fluid_parameters(), c.solid(c.l0));
  CHECK(coupler.structure_offset() == n_fluid_set);
  const auto& kinds = coupler.fluid().particles().kinds();
  const auto& xs = coupler.solid().particles().positions();
  REQUIRE(kinds.size() == n_fluid_set + xs.size());
  const double depth = c.scene.clamp_columns * c.l0;
  for (std::size_t s = 0; s < xs.size(); ++s) {
    const double x = xs[s][0], y = xs[s][1];
    // Interior: dummy. Bottom row, wetted top row, the rows near the free end faces: wall.
    const bool outer = y > -c.l0 || y < -c.scene.thickness + c.l0 || x < -depth + 2 * c.l0 ||
                       x > c.scene.span + depth - 2 * c.l0;
    // The top row under the side walls, all but its corner particle, is covered by them: dummy.
    const bool covered = y > -c.l0 && ((x < 0 && x > -depth + c.l0) || (x > c.scene.span && x < c.scene.span + depth - c.l0));
    CAPTURE(x);
    CAPTURE(y);
    CHECK(kinds[n_fluid_set + s] == (outer && !covered ? ParticleKind::wall : ParticleKind::dummy));
  }
}

// The plate continues under the tank's side walls (clamped there). Its top row under them is
// structure surface, but its outward site lies inside the walls: as a strip of wall particles it
// would carry the PPE's pressure down to the P = 0 end faces and draw the corner water in. Covered
// particles join the fluid as dummy and take no load; the option off restores every surface
// particle as a wall.
TEST_CASE("fsi.coupler: structure surface covered by the tank's walls is dummy and takes no load") {
  SmallCase c;
  std::vector<std::size_t> top_under_walls;
  {
    const auto plate = c.solid(c.l0);
    const auto& xs = plate.particles().positions();
    for (std::size_t s = 0; s < xs.size(); ++s)
      if (xs[s][1] > -c.l0 && (xs[s][0] < 0 || xs[s][0] > c.scene.span)) top_under_walls.push_back(s);
  }
  REQUIRE(top_under_walls.size() == 2 * static_cast<std::size_t>(c.scene.clamp_columns));
  for (const bool cover : {true, false}) {
    CAPTURE(cover);
    CouplingParameters cp;
    cp.covered_surface_as_dummy = cover;
    FsiCoupler<FluidSolver<2>, ElasticSolver<2>> coupler(c.scene.fluid_particles(c.l0), c.fluid_parameters(),
                                                         c.solid(c.l0), cp);
    coupler.step();
    const auto& kinds = coupler.fluid().particles().kinds();
    const auto& xs = coupler.solid().particles().positions();
    std::size_t covered = 0;
    for (const auto s : top_under_walls) {
      const bool dummy = kinds[coupler.structure_offset() + s] == ParticleKind::dummy;
      CHECK(dummy == !coupler.on_surface()[s]);
      if (dummy) {
        ++covered;
        CHECK(coupler.interface_force()[s].norm() == 0);
      }
    }
    // All but the corner particle at each end face (its outward site is diagonal, off the wall
    // lattice) are covered; none without the option.
    CHECK(covered == (cover ? top_under_walls.size() - 2 : 0));
    // The wetted top row between the walls stays wall either way and carries the load.
    for (std::size_t s = 0; s < xs.size(); ++s)
      if (xs[s][1] > -c.l0 && xs[s][0] > 0 && xs[s][0] < c.scene.span)
        CHECK(kinds[coupler.structure_offset() + s] == ParticleKind::wall);
    CHECK(coupler.total_interface_force()[1] < 0);
  }
}

TEST_CASE("fsi.coupler: one step keeps fluid and structure in time and loads the plate downwards") {
  SmallCase c;
  SUBCASE("explicit") {
    FsiCoupler<FluidSolver<2>, ElasticSolver<2>> coupler(c.scene.fluid_particles(c.l0), c.fluid_parameters(), c.solid(c.l0));
    coupler.step();
    CHECK(coupler.last_iterations() == 1);
    CHECK(coupler.last_substeps() >= 1);
    CHECK(coupler.solid().time() == doctest::Approx(coupler.time()).epsilon(1e-12));
    CHECK(coupler.total_interface_force()[1] < 0);
  }
  SUBCASE("sub-iterated") {
    FsiCoupler<FluidSolver<2>, ElasticSolver<2>, SubIterated> coupler(c.scene.fluid_particles(c.l0),
                                                                      c.fluid_parameters(), c.solid(c.l0));
    coupler.step();
    coupler.step();
    CHECK(coupler.last_iterations() >= 2);
    CHECK(coupler.solid().time() == doctest::Approx(coupler.time()).epsilon(1e-12));
    CHECK(coupler.total_interface_force()[1] < 0);
  }
  SUBCASE("interface quasi-Newton") {
    FsiCoupler<FluidSolver<2>, ElasticSolver<2>, InterfaceQuasiNewton> coupler(c.scene.fluid_particles(c.l0),
                                                                               c.fluid_parameters(), c.solid(c.l0));
    coupler.step();
    coupler.step();
    CHECK(coupler.last_iterations() >= 2);
    CHECK(coupler.last_iterations() <= InterfaceQuasiNewton{}.max_iterations);
    CHECK(coupler.solid().time() == doctest::Approx(coupler.time()).epsilon(1e-12));
    CHECK(coupler.total_interface_force()[1] < 0);
  }
}

// Coupling schemes that misuse the coupler's Step: each is a clear InvalidInput, not a step
// that silently leaves the fluid and the structure at different times.
struct SkipsTheStructure {
  static constexpr bool iterative = false;
  static constexpr const char* name = "skips the structure";
  template <class Step>
  void advance(Step& step) const {
    step.solve_fluid();
  }
};
struct RepeatsWithoutKeepingTheStart {
  static constexpr bool iterative = false;
  static constexpr const char* name = "repeats";
  template <class Step>
  void advance(Step& step) const {
    step.solve_fluid();
    step.solve_fluid();
  }
};
struct LoadsBeforeSolving {
  static constexpr bool iterative = false;
  static constexpr const char* name = "loads first";
  template <class Step>
  void advance(Step& step) const {
    step.fluid_load(step.load());
  }
};

TEST_CASE("fsi.coupler: a coupling scheme that misuses the step is refused with a clear error") {
  SmallCase c;
  const auto fails_with = [&](auto scheme, const char* what) {
    FsiCoupler<FluidSolver<2>, ElasticSolver<2>, decltype(scheme)> coupler(c.scene.fluid_particles(c.l0),
                                                                           c.fluid_parameters(), c.solid(c.l0));
    CHECK_THROWS_WITH_AS(coupler.step(), doctest::Contains(what), InvalidInput);
  };
  fails_with(SkipsTheStructure{}, "'skips the structure' ended a step without advancing the structure");
  fails_with(RepeatsWithoutKeepingTheStart{}, "'repeats' solved the fluid twice in one step but declares `iterative = false`");
  fails_with(LoadsBeforeSolving{}, "'loads first' called Step::fluid_load before the step's first solve_fluid");
}

// A user's load on the structure (applied_force) adds to the fluid's: a downward force on the
// plate's middle particle moves it further down than the water alone; bad entries are refused.
TEST_CASE("fsi.coupler: an applied force adds to the fluid's load, and a bad one is refused") {
  SmallCase c;
  auto displacement = [&](double force) {
    FsiCoupler<FluidSolver<2>, ElasticSolver<2>> coupler(c.scene.fluid_particles(c.l0), c.fluid_parameters(), c.solid(c.l0));
    const double y0 = coupler.solid().particles().positions()[c.middle][1];
    coupler.applied_force()[c.middle] = Vec<2>(0, -force);
    for (int k = 0; k < 3; ++k) coupler.step();
    return coupler.solid().particles().positions()[c.middle][1] - y0;
  };
  const double water_only = displacement(0), pushed = displacement(1e3);
  INFO("middle particle moved " << water_only << " m by the water, " << pushed << " m with the force");
  CHECK(pushed < water_only);

  FsiCoupler<FluidSolver<2>, ElasticSolver<2>> coupler(c.scene.fluid_particles(c.l0), c.fluid_parameters(), c.solid(c.l0));
  coupler.applied_force()[0] = Vec<2>(std::nan(""), 0);
  CHECK_THROWS_WITH_AS(coupler.step(), doctest::Contains("applied_force() of structure particle 0 is not finite"),
                       InvalidInput);
  coupler.applied_force()[0] = Vec<2>::Zero();
  coupler.applied_force().pop_back();
  CHECK_THROWS_WITH_AS(coupler.step(), doctest::Contains("one entry per structure particle"), InvalidInput);
}

// The 3D gate scene is the 2D one extruded along z, so y is its vertical in 3D too. With the
// fluid's default gravity (the last axis) the 3D example once had gravity across the width: the
// pressure fell linearly from one side wall to the other, the gate took a fraction of its load
// and deflected a quarter as far as in 2D. After one coupled step with the scene's gravity, the
// pressure in the tank (away from the gate) must be the same in every z layer and rise with depth.
TEST_CASE("fsi.elastic_gate: the 3D extrusion is loaded along y, uniformly across its width") {
  const scenes::ElasticGate scene;
  const double l0 = 0.0025;
  std::vector<std::size_t> clamped;
  std::size_t tip = 0;
  SolidParameters<3> sp;
  sp.l0 = l0;
  scene.set_material(sp);
  sp.gravity = scene.gravity_vector<3>();
  ElasticSolver<3> gate(scene.gate_particles<3>(l0, clamped, tip), sp);
  for (auto i : clamped) gate.clamp(i);
  FluidParameters<3> fp;
  fp.l0 = l0;
  fp.gravity = scene.gravity_vector<3>();
  FsiCoupler<FluidSolver<3>, ElasticSolver<3>, ExplicitPartitioned> coupler(scene.fluid_particles<3>(l0), fp,
                                                                             std::move(gate));
  coupler.step();
  const auto& set = coupler.fluid().particles();
  const auto& p = coupler.fluid().pressure();
  // Mean pressure per z layer (8 layers) in x in [0.02, 0.08] m, and in two bands of height.
  std::vector<double> layer_sum(8, 0.0), layer_count(8, 0.0);
  double low = 0, high = 0, n_low = 0, n_high = 0;
  for (std::size_t i = 0; i < set.size(); ++i) {
    if (set.kinds()[i] != ParticleKind::fluid) continue;
    const Vec<3>& x = set.positions()[i];
    if (x[0] < 0.02 || x[0] > 0.08) continue;
    if (x[1] > 0.02 && x[1] < 0.04) {
      low += p[i];
      ++n_low;
    } else if (x[1] > 0.08 && x[1] < 0.10) {
      high += p[i];
      ++n_high;
    }
    if (x[1] < 0.02 || x[1] > 0.10) continue;
    const auto k = static_cast<std::size_t>(std::clamp(std::floor(x[2] / l0), 0.0, 7.0));
    layer_sum[k] += p[i];
    layer_count[k] += 1;
  }
  REQUIRE(n_low > 0);
  REQUIRE(n_high > 0);
  double lo = 1e300, hi = -1e300;
  for (std::size_t k = 0; k < 8; ++k) {
    REQUIRE(layer_count[k] > 0);
    lo = std::min(lo, layer_sum[k] / layer_count[k]);
    hi = std::max(hi, layer_sum[k] / layer_count[k]);
  }
  INFO("layer means " << lo << " .. " << hi << " Pa; lower band " << low / n_low << ", upper band " << high / n_high);
  CHECK(lo > 0);
  CHECK(hi - lo < 0.05 * hi);  // gravity along z (across the channel) gives layer means of 0 .. 86 Pa
  CHECK(low / n_low > high / n_high);
}

}  // TEST_SUITE
