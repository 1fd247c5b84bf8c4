// SPDX-License-Identifier: BSD-3-Clause
#include <doctest/doctest.h>

#include <cmath>

#include "mpsfsi/fluid/fluid_solver.hpp"
#include "mpsfsi/scenes/tank.hpp"

using namespace mpsfsi;

namespace {

ParticleSet<2> small_tank() {
  ParticleSet<2> set;
  scenes::add_block<2, double>(set, Vec<2>(0, 0), Vec<2>(0.05, 0.05), 0.005, ParticleKind::fluid);
  scenes::add_tank<2, double>(set, Vec<2>(0.05, 0.08), 0.005);
  return set;
}

}  // namespace

TEST_SUITE("fluid") {

TEST_CASE("fluid.fluid_solver: bad input gets a clear error") {
  FluidParameters<2> p;
  SUBCASE("missing l0") { CHECK_THROWS_WITH_AS(FluidSolver<2>(small_tank(), p), doctest::Contains("l0"), InvalidInput); }
  p.l0 = 0.005;
  SUBCASE("empty set") { CHECK_THROWS_WITH_AS(FluidSolver<2>(ParticleSet<2>{}, p), doctest::Contains("empty"), InvalidInput); }
  SUBCASE("no fluid") {
    ParticleSet<2> walls;
    scenes::add_tank<2, double>(walls, Vec<2>(0.05, 0.05), 0.005);
    CHECK_THROWS_WITH_AS(FluidSolver<2>(std::move(walls), p), doctest::Contains("no fluid"), InvalidInput);
  }
  SUBCASE("overlapping particles") {
    auto set = small_tank();
    set.add(set.positions()[3]);
    CHECK_THROWS_WITH_AS(FluidSolver<2>(std::move(set), p), doctest::Contains("overlap"), InvalidInput);
  }
  SUBCASE("NaN position") {
    auto set = small_tank();
    set.positions()[5][1] = std::nan("");
    CHECK_THROWS_WITH_AS(FluidSolver<2>(std::move(set), p), doctest::Contains("particle 5"), InvalidInput);
  }
  SUBCASE("time step above the stability limit") {
    p.dt = 0.1;
    FluidSolver<2> solver(small_tank(), p);
    CHECK_THROWS_WITH_AS(solver.step(), doctest::Contains("stability limit"), InvalidInput);
  }
  SUBCASE("negative density") {
    p.density = -1;
    CHECK_THROWS_WITH_AS(FluidSolver<2>(small_tank(), p), doctest::Contains("density"), InvalidInput);
  }
}

TEST_CASE("fluid.fluid_solver: a PPE that cannot converge is reported with step and time") {
  FluidParameters<2> p;
  p.l0 = 0.005;
  p.dt = 1e-4;
  p.ppe_max_iterations = 1;
  FluidSolver<2> solver(small_tank(), p);
  try {
    solver.step();
    FAIL("expected a SimulationError");
  } catch (const SimulationError& e) {
    CHECK(e.step() == 1);
    CHECK(e.time() == doctest::Approx(1e-4));
    CHECK(std::string(e.what()).find("did not converge") != std::string::npos);
  }
  CHECK(solver.step_count() == 0);  // the state is the last good one
}

TEST_CASE("fluid.fluid_solver: a fluid at rest in free fall without walls falls at g") {
  // A block with no walls: every particle gets the same acceleration; pressure stays zero-ish.
  ParticleSet<2> set;
  scenes::add_block<2, double>(set, Vec<2>(0, 0), Vec<2>(0.03, 0.03), 0.005, ParticleKind::fluid);
  FluidParameters<2> p;
  p.l0 = 0.005;
  p.dt = 1e-4;
  FluidSolver<2> solver(std::move(set), p);
  for (int k = 0; k < 50; ++k) solver.step();
  double mean_vy = 0;
  for (const auto& u : solver.particles().velocities()) mean_vy += u[1];
  mean_vy /= static_cast<double>(solver.particles().size());
  // Momentum: gravity alone acts on the set as a whole; pressure forces of the MPS gradient are
  // not exactly antisymmetric, so the mean velocity is held to 1 %.
  CHECK(std::abs(mean_vy - (-9.81 * 50 * 1e-4)) <= 0.01 * 9.81 * 50 * 1e-4);
}

TEST_CASE("fluid.fluid_solver: wall particles move with the velocity they are given") {
  // The tank slides right at 0.05 m/s; its particles must translate rigidly, untouched by the
  // PPE, and the water must be dragged along (its mean velocity approaches the tank's).
  FluidParameters<2> p;
  p.l0 = 0.005;
  p.dt = 2e-4;
  FluidSolver<2> solver(small_tank(), p);
  auto& set = solver.particles();
  const Vec<2> v(0.05, 0);
  std::vector<Vec<2>> start;
  for (std::size_t i = 0; i < set.size(); ++i) {
    if (set.kinds()[i] != ParticleKind::fluid) set.velocities()[i] = v;
    start.push_back(set.positions()[i]);
  }
  const int steps = 500;
  for (int k = 0; k < steps; ++k) solver.step();
  double worst = 0, fluid_vx = 0;
  std::size_t fluid = 0;
  for (std::size_t i = 0; i < set.size(); ++i) {
    if (set.kinds()[i] == ParticleKind::fluid) {
      fluid_vx += set.velocities()[i][0];
      ++fluid;
      continue;
    }
    worst = std::max(worst, (set.positions()[i] - start[i] - steps * p.dt * v).norm());
    CHECK(set.velocities()[i] == v);
  }
  CHECK(worst < 1e-12);
  fluid_vx /= static_cast<double>(fluid);
  MESSAGE("mean fluid velocity after 0.1 s in a tank sliding at 0.05 m/s: " << fluid_vx);
  CHECK(fluid_vx > 0.5 * v[0]);
}

}  // TEST_SUITE
