// SPDX-License-Identifier: BSD-3-Clause
#include <doctest/doctest.h>

#include "mpsfsi/fluid/fluid_solver.hpp"
#include "mpsfsi/fsi/fsi_coupler.hpp"
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
  for (std::size_t s = 0; s < xs.size(); ++s) {
    const bool outer = xs[s][1] > -c.l0 || xs[s][1] < -c.scene.thickness + c.l0 || xs[s][0] < -2.5 * c.l0 ||
                       xs[s][0] > c.scene.span + 2.5 * c.l0;
    CHECK(kinds[n_fluid_set + s] == (outer ? ParticleKind::wall : ParticleKind::dummy));
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
}

}  // TEST_SUITE
