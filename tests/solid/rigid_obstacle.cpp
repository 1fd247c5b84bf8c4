// SPDX-License-Identifier: BSD-3-Clause
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "mpsfsi/core/error.hpp"
#include "mpsfsi/io/checkpoint.hpp"
#include "mpsfsi/scenes/solid_block.hpp"
#include "mpsfsi/solid/elastic_solver.hpp"
#include "mpsfsi/solid/rigid_obstacle.hpp"
#include "support/motion_fit.hpp"

using namespace mpsfsi;

namespace {

constexpr double kPi = 3.14159265358979323846;

SolidParameters<2> block_parameters(double l0) {
  SolidParameters<2> p;
  p.l0 = l0;
  p.density = 1000;
  p.youngs_modulus = 1e7;
  p.poisson_ratio = 0.3;
  p.gravity = Vec<2>::Zero();
  return p;
}

double mean_x(const ElasticSolver<2>& s) {
  double x = 0;
  for (const auto& p : s.particles().positions()) x += p[0];
  return x / static_cast<double>(s.particles().size());
}

Vec<2> momentum(const ElasticSolver<2>& s) {
  Vec<2> m = Vec<2>::Zero();
  for (const auto& v : s.particles().velocities()) m += s.particle_mass() * v;
  return m;
}

// An elastic block (16 x 4 spacings) on the floor y < 0, its weight tilted by `slope` radians so
// that the floor is a slope, friction mu: returns the fitted down-slope acceleration of its centre
// after the load has rung down, or its travel when it is stuck. The weight is applied as an
// external force ramped up over 0.03 s: a suddenly applied weight overshoots, the friction
// springs and the normal ones at different frequencies, and a block within 10 % of the threshold
// then slips (docs/validation/solid.md, "Friction on a slope").
struct SlopeRun {
  double acceleration = 0;
  double travel = 0;
};

SlopeRun slide_on_rigid_slope(double slope, double mu) {
  const double l0 = 0.01;
  const double g = 9.81;
  SolidParameters<2> p = block_parameters(l0);
  p.contact_damping_ratio = 0.5;  // settles the block's load onto the floor without bouncing
  p.bond_viscosity = 0.2;         // damps the block's own ringing
  ElasticSolver<2> s(scenes::material_block<2>(Vec<2>(0, 0), Vec<2>(0.16, 0.04), l0), p);
  auto floor = RigidObstacle<2>::half_space(Vec<2>(0, 0), Vec<2>(0, 1));
  floor.set_friction(mu);
  s.add_obstacle(floor);
  const Vec<2> weight = s.particle_mass() * g * Vec<2>(std::sin(slope), -std::cos(slope));
  const double ramp = 0.03, settle = 0.05;
  std::vector<double> t, x;
  while (s.time() < 0.15) {
    for (auto& f : s.external_force()) f = std::min(1.0, s.time() / ramp) * weight;
    s.step();
    if (s.time() >= settle) {
      t.push_back(s.time());
      x.push_back(mean_x(s));
    }
  }
  return {test::fitted_acceleration(t, x), mean_x(s) - x.front()};
}

// A free block (no gravity) moving at `speed` along x into a wedge whose face rises at angle
// alpha: it slides up the face. Returns the impulse the block gives the wedge while it does.
Vec<2> impulse_on_slope(double alpha, double mu, double speed) {
  const double l0 = 0.01;
  SolidParameters<2> p = block_parameters(l0);
  auto set = scenes::material_block<2>(Vec<2>(0, 0), Vec<2>(0.1, 0.03), l0);
  for (auto& v : set.velocities()) v = Vec<2>(speed, 0);
  ElasticSolver<2> s(set, p);
  // The face rises at alpha through (0.105, 0), just ahead of the block; the wedge lies to its right.
  const Vec<2> foot(0.105 - 0.05 / std::tan(alpha), -0.05), top = foot + 0.3 * Vec<2>(std::cos(alpha), std::sin(alpha));
  auto wedge = RigidObstacle<2>::polygon({foot, Vec<2>(top[0] + 0.2, foot[1]), top});
  wedge.set_friction(mu);
  s.add_obstacle(wedge);
  Vec<2> impulse = Vec<2>::Zero();
  while (s.time() < 0.03) {
    const Vec<2> before = s.obstacle(0).load();
    s.step();
    impulse += 0.5 * s.last_dt() * (before + s.obstacle(0).load());
  }
  return impulse;
}

}  // namespace

TEST_SUITE("solid") {

// Analytic: on a slope of angle alpha with Coulomb friction mu a block sticks when
// tan(alpha) <= mu and otherwise slides with a = g (sin(alpha) - mu cos(alpha)). The floor is
// flat, so no bump slows the block: frictionless, it slides at g sin(alpha) to the fit's
// precision (0.1 %). Sliding with friction, the block rings (steady sliding of an elastic body
// with Coulomb friction is not stable), and the friction coefficient its motion implies,
// (g sin(alpha) - a) / (g cos(alpha)), is mu to 1 % (0.16 % measured: docs/validation/solid.md,
// "On a rigid slope").
TEST_CASE("solid.obstacle: a block on a rigid slope sticks below tan(alpha) = mu and slides above it at g (sin - mu cos)") {
  const double g = 9.81;
  const double mu = 0.4;
  for (const double tangent : {0.1, 0.6}) {
    const double alpha = std::atan(tangent);
    const SlopeRun run = slide_on_rigid_slope(alpha, 0);
    MESSAGE("mu = 0, tan(alpha) = " << tangent << ": a = " << run.acceleration << " m/s^2 against " << g * std::sin(alpha));
    CHECK(run.acceleration == doctest::Approx(g * std::sin(alpha)).epsilon(0.001));
  }
  for (const double ratio : {0.8, 0.95}) {
    const SlopeRun run = slide_on_rigid_slope(std::atan(ratio * mu), mu);
    MESSAGE("mu = 0.4, tan(alpha) = " << ratio << " mu: travel " << run.travel << " m");
    CHECK(std::abs(run.travel) < 1e-5);  // 0.1 % of a spacing in 0.1 s: stuck
  }
  for (const double ratio : {1.1, 1.5}) {
    const double alpha = std::atan(ratio * mu);
    const SlopeRun run = slide_on_rigid_slope(alpha, mu);
    const double expected = g * (std::sin(alpha) - mu * std::cos(alpha));
    const double implied_mu = (g * std::sin(alpha) - run.acceleration) / (g * std::cos(alpha));
    MESSAGE("mu = 0.4, tan(alpha) = " << ratio << " mu: a = " << run.acceleration << " m/s^2 against " << expected
                                      << ", implied mu " << implied_mu);
    CHECK(implied_mu == doctest::Approx(mu).epsilon(0.01));
    CHECK(run.travel > 0.5 * 0.5 * expected * 0.1 * 0.1);  // it does slide
  }
}

// Analytic: ice sliding up a face at angle alpha pushes it with the normal force N and drags it
// up the face with mu N, so the horizontal and vertical loads stand in the ratio
// xi = (sin(alpha) + mu cos(alpha)) / (cos(alpha) - mu sin(alpha)) (Croasdale's slope factor,
// docs/theory.md, section 3.5). The ratio departs from xi only in the first instants of each
// particle's contact, while its friction spring is still below the cap (0.02 % measured).
TEST_CASE("solid.obstacle: a block sliding up a rigid slope loads it in the ratio (sin + mu cos) / (cos - mu sin)") {
  for (const double degrees : {45.0, 60.0})
    for (const double mu : {0.0, 0.1}) {
      const double alpha = degrees * kPi / 180;
      const Vec<2> impulse = impulse_on_slope(alpha, mu, 2.0);
      const double xi = (std::sin(alpha) + mu * std::cos(alpha)) / (std::cos(alpha) - mu * std::sin(alpha));
      MESSAGE("alpha = " << degrees << " deg, mu = " << mu << ": H/V = " << impulse[0] / -impulse[1] << " against " << xi);
      REQUIRE(impulse[0] > 0);
      CHECK(impulse[0] / -impulse[1] == doctest::Approx(xi).epsilon(0.001));
    }
}

// Newton's third law: the impulse of the obstacle's load, integrated as the velocity-Verlet step
// applies forces (the mean of the step's two ends), is what the block's momentum lost; the
// obstacle moves at its prescribed velocity whatever pushes back.
TEST_CASE("solid.obstacle: a moving wall pushes a free block; the load's impulse is the block's momentum") {
  const double l0 = 0.01;
  SolidParameters<2> p = block_parameters(l0);
  p.contact_friction = 0.3;
  ElasticSolver<2> s(scenes::material_block<2>(Vec<2>(0, 0), Vec<2>(0.06, 0.04), l0), p);
  const Vec<2> wall_velocity(1.0, 0.2);
  const std::size_t k = s.add_obstacle(RigidObstacle<2>::half_space(Vec<2>(-0.02, 0), Vec<2>(1, 0)));
  s.obstacle(k).set_velocity(wall_velocity);
  const Vec<2> p0 = momentum(s);
  Vec<2> impulse = Vec<2>::Zero();
  std::size_t most_touching = 0;
  while (s.time() < 0.05) {
    const Vec<2> before = s.obstacle(k).load();
    s.step();
    impulse += 0.5 * s.last_dt() * (before + s.obstacle(k).load());
    most_touching = std::max(most_touching, s.obstacle(k).touching_particles());
  }
  CHECK(most_touching >= 4);  // the whole left face of the block
  CHECK(s.obstacle(k).displacement()[0] == doctest::Approx(wall_velocity[0] * s.time()).epsilon(1e-12));
  CHECK(s.obstacle(k).displacement()[1] == doctest::Approx(wall_velocity[1] * s.time()).epsilon(1e-12));
  const Vec<2> gained = momentum(s) - p0;
  CHECK(gained[0] > 0.5 * s.particle_mass() * static_cast<double>(s.particles().size()) * wall_velocity[0]);
  CHECK((gained + impulse).norm() < 1e-9 * gained.norm());
  CHECK(gained[1] > 0);  // friction drags the block along the wall's sliding
}

// Statics: a block at rest on a floor weighs on it with its weight, in 2D and in 3D.
TEST_CASE("solid.obstacle: a block resting on a floor loads it with its weight (2D and 3D)") {
  const double l0 = 0.01, g = 9.81;
  SolidParameters<2> p = block_parameters(l0);
  p.gravity = Vec<2>(0, -g);
  p.damping = 200;  // dynamic relaxation to rest
  ElasticSolver<2> s(scenes::material_block<2>(Vec<2>(0, 0), Vec<2>(0.08, 0.04), l0), p);
  s.add_obstacle(RigidObstacle<2>::half_space(Vec<2>(0, 0), Vec<2>(0, 1)));
  s.advance_to(0.1);
  const double weight = s.particle_mass() * static_cast<double>(s.particles().size()) * g;
  CHECK(s.obstacle(0).load()[1] == doctest::Approx(-weight).epsilon(1e-4));
  CHECK(std::abs(s.obstacle(0).load()[0]) < 1e-9 * weight);

  SolidParameters<3> p3;
  p3.l0 = l0;
  p3.density = 1000;
  p3.youngs_modulus = 1e7;
  p3.poisson_ratio = 0.3;
  p3.gravity = Vec<3>(0, 0, -g);
  p3.damping = 200;
  ElasticSolver<3> s3(scenes::material_block<3>(Vec<3>(0, 0, 0), Vec<3>(0.04, 0.03, 0.03), l0), p3);
  // A polygon in the (x, z) plane swept along y: a box whose top face z = 0 is the floor.
  s3.add_obstacle(RigidObstacle<3>::polygon({Vec<2>(-1, -1), Vec<2>(1, -1), Vec<2>(1, 0), Vec<2>(-1, 0)}));
  s3.advance_to(0.1);
  const double weight3 = s3.particle_mass() * static_cast<double>(s3.particles().size()) * g;
  CHECK(s3.obstacle(0).load()[2] == doctest::Approx(-weight3).epsilon(1e-4));
  CHECK(s3.obstacle(0).touching_particles() == 12);  // the bottom layer, 4 x 3
}

// A fixed frictionless floor is a conservative force: a block dropped on it bounces off with its
// total energy (kinetic, elastic with the floor's springs, gravity) as it was, to the
// symplectic integrator's error. While the springs are pressed the energy the step keeps differs
// from the true one by O((omega dt)^2) of the springs' energy (omega dt = 0.2 for the contact
// spring here); that difference returns to zero when the block has left the floor, but for the
// same difference on the block's own ringing (2e-5 of the impact's kinetic energy measured).
TEST_CASE("solid.obstacle: a block bouncing on a fixed frictionless floor keeps its energy") {
  const double l0 = 0.01;
  SolidParameters<2> p = block_parameters(l0);
  p.gravity = Vec<2>(0, -9.81);
  auto set = scenes::material_block<2>(Vec<2>(0, 0.001), Vec<2>(0.06, 0.031), l0);
  for (auto& v : set.velocities()) v = Vec<2>(0.3, -1.0);
  ElasticSolver<2> s(set, p);
  s.add_obstacle(RigidObstacle<2>::half_space(Vec<2>(0, 0), Vec<2>(0, 1)));
  const double e0 = s.total_energy(), impact = s.kinetic_energy();
  double during = 0;
  std::size_t most_touching = 0;
  while (s.time() < 0.02) {
    s.step();
    during = std::max(during, std::abs(s.total_energy() - e0));
    most_touching = std::max(most_touching, s.obstacle(0).touching_particles());
  }
  const double after = std::abs(s.total_energy() - e0);
  MESSAGE("energy error: at most " << during / impact << ", after the bounce " << after / impact
                                   << " of the kinetic energy at impact");
  CHECK(most_touching == 6);                   // the whole bottom row hit the floor
  CHECK(s.obstacle(0).touching_particles() == 0);  // and has left it
  CHECK(after < 1e-4 * impact);
}

TEST_CASE("solid.obstacle: the distance to a convex polygon is the largest of its faces' (2D and 3D)") {
  const auto square = RigidObstacle<2>::polygon({Vec<2>(0, 0), Vec<2>(1, 0), Vec<2>(1, 1), Vec<2>(0, 1)});
  CHECK(square.distance(Vec<2>(0.5, 1.25)) == doctest::Approx(0.25));
  CHECK(square.distance(Vec<2>(-0.1, 0.5)) == doctest::Approx(0.1));
  CHECK(square.distance(Vec<2>(0.5, 0.4)) == doctest::Approx(-0.4));
  CHECK(square.distance(Vec<2>(1.3, 1.2)) == doctest::Approx(0.3));  // the extended face, not the corner's 0.36
  const auto prism = RigidObstacle<3>::polygon({Vec<2>(0, 0), Vec<2>(1, 0), Vec<2>(0, 1)});
  CHECK(prism.distance(Vec<3>(0.5, 7.0, -0.2)) == doctest::Approx(0.2));
  CHECK(prism.distance(Vec<3>(1.0, -3.0, 1.0)) == doctest::Approx(std::sqrt(0.5)));
}

// The obstacle's motion and friction anchors are part of the state: a run continued from a
// checkpoint gives the bits of a run straight through, and a solver with other obstacles cannot
// read it.
TEST_CASE("solid.obstacle: a moving obstacle with friction continued from a checkpoint gives the same bits") {
  const double l0 = 0.01;
  SolidParameters<2> p = block_parameters(l0);
  p.gravity = Vec<2>(0, -9.81);
  p.contact_friction = 0.4;
  auto make = [&] {
    ElasticSolver<2> s(scenes::material_block<2>(Vec<2>(0, 0), Vec<2>(0.06, 0.03), l0), p);
    s.add_obstacle(RigidObstacle<2>::half_space(Vec<2>(0, 0), Vec<2>(0, 1)));
    const std::size_t pusher = s.add_obstacle(RigidObstacle<2>::half_space(Vec<2>(-0.001, 0), Vec<2>(1, 0)));
    s.obstacle(pusher).set_velocity(Vec<2>(0.05, 0));  // pushes the block along the floor from 0.02 s on
    return s;
  };
  constexpr long long steps = 4000;
  ElasticSolver<2> straight = make();
  while (straight.step_count() < steps) straight.step();
  const std::string path = "solid_obstacle_checkpoint.bin";
  {
    ElasticSolver<2> first_part = make();
    while (first_part.step_count() < steps / 2) first_part.step();
    write_checkpoint(path, first_part);
  }
  ElasticSolver<2> resumed = make();
  read_checkpoint(path, resumed);
  while (resumed.step_count() < steps) resumed.step();
  CHECK(straight.obstacle(0).touching_particles() > 0);
  CHECK(mean_x(straight) > 0.03 + 0.001);  // the pusher has moved the block along the floor
  CHECK(resumed.particles().positions() == straight.particles().positions());
  CHECK(resumed.particles().velocities() == straight.particles().velocities());
  CHECK(resumed.obstacle(1).displacement() == straight.obstacle(1).displacement());
  ElasticSolver<2> other(scenes::material_block<2>(Vec<2>(0, 0), Vec<2>(0.06, 0.03), l0), p);
  CHECK_THROWS_WITH_AS(read_checkpoint(path, other), doctest::Contains("obstacles"), InvalidInput);
  std::remove(path.c_str());
}

TEST_CASE("solid.obstacle: bad shapes, motions and friction coefficients are errors naming the problem") {
  using Obstacle = RigidObstacle<2>;
  CHECK_THROWS_WITH_AS(Obstacle(std::vector<Obstacle::Face>{}), doctest::Contains("no faces"), InvalidInput);
  CHECK_THROWS_WITH_AS(Obstacle::half_space(Vec<2>(0, 0), Vec<2>(0, 0)), doctest::Contains("non-zero normal"),
                       InvalidInput);
  CHECK_THROWS_AS(Obstacle::half_space(Vec<2>(std::nan(""), 0), Vec<2>(0, 1)), InvalidInput);
  CHECK_THROWS_WITH_AS(Obstacle::polygon({Vec<2>(0, 0), Vec<2>(1, 0)}), doctest::Contains("three corners"), InvalidInput);
  CHECK_THROWS_WITH_AS(Obstacle::polygon({Vec<2>(0, 0), Vec<2>(0, 1), Vec<2>(1, 0)}),
                       doctest::Contains("counter-clockwise"), InvalidInput);
  CHECK_THROWS_WITH_AS(Obstacle::polygon({Vec<2>(0, 0), Vec<2>(2, 0), Vec<2>(1, 0.2), Vec<2>(1, 1), Vec<2>(0, 1)}),
                       doctest::Contains("convex"), InvalidInput);
  CHECK_THROWS_WITH_AS(Obstacle::polygon({Vec<2>(0, 0), Vec<2>(1, 0), Vec<2>(1, 0), Vec<2>(0, 1)}),
                       doctest::Contains("coincide"), InvalidInput);
  auto floor = Obstacle::half_space(Vec<2>(0, 0), Vec<2>(0, 1));
  CHECK_THROWS_AS(floor.set_friction(-0.1), InvalidInput);
  CHECK_THROWS_AS(floor.set_friction(std::nan("")), InvalidInput);
  CHECK_THROWS_AS(floor.set_velocity(Vec<2>(std::nan(""), 0)), InvalidInput);
  ElasticSolver<2> s(scenes::material_block<2>(Vec<2>(0, 0.01), Vec<2>(0.03, 0.03), 0.01), block_parameters(0.01));
  CHECK_THROWS_WITH_AS(s.obstacle(0), doctest::Contains("out of range"), InvalidInput);
}

}  // TEST_SUITE
