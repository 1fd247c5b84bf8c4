// SPDX-License-Identifier: BSD-3-Clause
#include <doctest/doctest.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "mpsfsi/core/error.hpp"
#include "mpsfsi/io/checkpoint.hpp"
#include "mpsfsi/scenes/solid_block.hpp"
#include "mpsfsi/solid/elastic_solver.hpp"
#include "support/motion_fit.hpp"

using namespace mpsfsi;

namespace {

// An elastic block resting on a clamped row of particles, gravity tilted by `slope` radians so
// that the row is a slope (the lattice stays axis-aligned). The row's spacing l0/1.7 is
// incommensurate with the block's, so the block's bottom particles sit at ten different offsets
// from the row's, and the contact distance is 2 l0, so that each bottom particle touches several
// of the row's: the surface is smooth to within its bumps, which still slow a frictionless block
// by about 1.5 % (docs/validation/solid.md, "Friction on a slope", measures them against the
// contact distance).
struct SlopeRun {
  double acceleration = 0;  // fitted down-slope acceleration of the block's centre of mass
  double travel = 0;        // down-slope displacement of the block after it has settled
};

ElasticSolver<2> block_on_slope(double slope, double mu, std::size_t& block) {
  const double l0 = 0.01;
  const double g = 9.81;
  auto set = scenes::material_block<2>(Vec<2>(0, 0), Vec<2>(0.16, 0.04), l0);
  block = set.size();
  const double spacing = l0 / 1.7;
  const double contact_distance = 2 * l0;
  const double row_y = 0.5 * l0 - contact_distance;  // one contact distance below the bottom row
  const auto row_count = static_cast<std::size_t>(std::ceil(0.29 / spacing));
  ParticleSet<2> row(row_count);
  for (std::size_t k = 0; k < row_count; ++k) {
    row.positions()[k] = Vec<2>(-0.03 + spacing * static_cast<double>(k), row_y);
    row.kinds()[k] = ParticleKind::solid;
  }
  scenes::append(set, row);
  std::vector<std::int32_t> body(set.size(), 0);
  for (std::size_t i = block; i < set.size(); ++i) body[i] = 1;
  SolidParameters<2> p;
  p.l0 = l0;
  p.density = 1000;
  p.youngs_modulus = 1e7;
  p.poisson_ratio = 0.3;
  p.gravity = Vec<2>(g * std::sin(slope), -g * std::cos(slope));
  p.contact_friction = mu;
  p.contact_distance_ratio = contact_distance / l0;
  p.contact_damping_ratio = 0.5;  // settles the block's first load onto the row without bouncing
  p.bond_viscosity = 0.2;         // damps the block's own ringing
  ElasticSolver<2> s(set, p, body);
  for (std::size_t i = block; i < set.size(); ++i) s.clamp(i);
  return s;
}

SlopeRun slide_on_slope(double slope, double mu, double duration) {
  std::size_t block = 0;
  ElasticSolver<2> s = block_on_slope(slope, mu, block);
  auto centre = [&] {
    double x = 0;
    for (std::size_t i = 0; i < block; ++i) x += s.particles().positions()[i][0];
    return x / static_cast<double>(block);
  };
  const double settle = 0.05;  // the block's first load onto the row rings down within it
  std::vector<double> t, x;
  while (s.time() < duration) {
    s.step();
    if (s.time() >= settle) {
      t.push_back(s.time());
      x.push_back(centre());
    }
  }
  SlopeRun run;
  run.acceleration = test::fitted_acceleration(t, x);
  run.travel = centre() - x.front();
  return run;
}

}  // namespace

TEST_SUITE("solid") {

// Analytic: a block on a slope of angle alpha with Coulomb friction mu sticks when
// tan(alpha) <= mu and otherwise slides down with a = g (sin(alpha) - mu cos(alpha)). The 3 %
// is the surface's own bumps (the frictionless block: 1.2-1.7 % slow) with a margin.
TEST_CASE("solid.contact: a block on a slope sticks below tan(alpha) = mu and slides above it at g (sin - mu cos)") {
  const double g = 9.81;
  const double mu = 0.4;
  const double duration = 0.15;
  for (const double tangent : {0.1, 0.6}) {
    const double alpha = std::atan(tangent);
    const SlopeRun run = slide_on_slope(alpha, 0, duration);
    const double expected = g * std::sin(alpha);
    MESSAGE("mu = 0, tan(alpha) = " << tangent << ": a = " << run.acceleration << " m/s^2 against " << expected);
    CHECK(run.acceleration == doctest::Approx(expected).epsilon(0.03));
  }
  for (const double ratio : {0.8, 0.95}) {
    const SlopeRun run = slide_on_slope(std::atan(ratio * mu), mu, duration);
    MESSAGE("mu = 0.4, tan(alpha) = " << ratio << " mu: travel " << run.travel << " m");
    CHECK(std::abs(run.travel) < 1e-5);  // 0.1 % of a spacing in 0.1 s: stuck
  }
  for (const double ratio : {1.1, 1.5}) {
    const double alpha = std::atan(ratio * mu);
    const SlopeRun run = slide_on_slope(alpha, mu, duration);
    const double expected = g * (std::sin(alpha) - mu * std::cos(alpha));
    MESSAGE("mu = 0.4, tan(alpha) = " << ratio << " mu: a = " << run.acceleration << " m/s^2 against " << expected);
    CHECK(run.acceleration == doctest::Approx(expected).epsilon(0.03));
    CHECK(run.travel > 0.5 * 0.5 * expected * 0.1 * 0.1);  // it does slide
  }
}

// A Verlet-list rebuild (here forced by cutting bonds inside the block) keeps the anchors of the
// pairs that stay in contact: the sticking springs hold the same energy before and after it.
TEST_CASE("solid.contact: a rebuild of the contact list keeps the sticking pairs' anchors") {
  std::size_t block = 0;
  ElasticSolver<2> s = block_on_slope(std::atan(0.8 * 0.4), 0.4, block);
  while (s.time() < 0.05) s.step();
  const double held = s.contact().friction_energy();
  const std::size_t rebuilds = s.contact().rebuilds();
  REQUIRE(held > 0);
  std::size_t top = 0;
  for (std::size_t i = 0; i < block; ++i)
    if (s.particles().positions()[i][1] > s.particles().positions()[top][1]) top = i;
  REQUIRE(s.impose_crack(top, Vec<2>(1, 0)) > 0);
  CHECK(s.contact().rebuilds() == rebuilds + 1);
  CHECK(s.contact().friction_energy() == doctest::Approx(held).epsilon(1e-12));
}

// The anchors of the sticking pairs are part of the state: a sliding block continued from a
// checkpoint, past Verlet-list rebuilds, gives the bits of a run straight through.
TEST_CASE("solid.contact: a sliding block with friction continued from a checkpoint gives the same bits") {
  const double alpha = std::atan(1.5 * 0.4);
  constexpr long long steps = 8000;
  std::size_t block = 0;
  ElasticSolver<2> straight = block_on_slope(alpha, 0.4, block);
  while (straight.step_count() < steps) straight.step();
  const std::string path = "solid_contact_friction_checkpoint.bin";
  {
    ElasticSolver<2> first_part = block_on_slope(alpha, 0.4, block);
    while (first_part.step_count() < steps / 2) first_part.step();
    write_checkpoint(path, first_part);
  }
  ElasticSolver<2> resumed = block_on_slope(alpha, 0.4, block);
  read_checkpoint(path, resumed);
  while (resumed.step_count() < steps) resumed.step();
  CHECK(straight.contact().rebuilds() > 3);  // some of them after the checkpoint
  CHECK(resumed.particles().positions() == straight.particles().positions());
  CHECK(resumed.particles().velocities() == straight.particles().velocities());
  std::remove(path.c_str());
}

// The friction forces of a pair are equal and opposite to the bit (contact.hpp), so two free
// bodies rubbing past each other keep their total momentum.
TEST_CASE("solid.contact: friction between two free bodies keeps their momentum") {
  const double l0 = 0.01;
  auto set = scenes::material_block<2>(Vec<2>(0, 0), Vec<2>(0.05, 0.03), l0);
  const std::size_t first_b = scenes::append(set, scenes::material_block<2>(Vec<2>(0.02, 0.029), Vec<2>(0.07, 0.059), l0));
  std::vector<std::int32_t> body(set.size(), 0);
  for (std::size_t i = first_b; i < set.size(); ++i) {
    body[i] = 1;
    set.velocities()[i] = Vec<2>(1.0, -0.2);
  }
  SolidParameters<2> p;
  p.l0 = l0;
  p.density = 1000;
  p.youngs_modulus = 1e6;
  p.poisson_ratio = 0.3;
  p.contact_friction = 0.5;
  ElasticSolver<2> s(set, p, body);
  auto momentum = [&] {
    Vec<2> m = Vec<2>::Zero();
    for (const auto& v : s.particles().velocities()) m += s.particle_mass() * v;
    return m;
  };
  const Vec<2> m0 = momentum();
  double slowed = 0;
  while (s.time() < 0.02) {
    s.step();
    double vb = 0;
    for (std::size_t i = first_b; i < set.size(); ++i) vb += s.particles().velocities()[i][0];
    slowed = std::max(slowed, 1.0 - vb / static_cast<double>(set.size() - first_b));
  }
  CHECK(slowed > 0.01);  // friction acted on the upper body's sliding
  CHECK((momentum() - m0).norm() < 1e-9 * m0.norm());
}

TEST_CASE("solid.contact: friction needs a contact policy that has it, and a finite mu >= 0") {
  const double l0 = 0.01;
  auto set = scenes::material_block<2>(Vec<2>(0, 0), Vec<2>(0.03, 0.03), l0);
  SolidParameters<2> p;
  p.l0 = l0;
  p.density = 1000;
  p.youngs_modulus = 1e6;
  p.poisson_ratio = 0.3;
  p.contact_friction = -0.1;
  CHECK_THROWS_AS(ElasticSolver<2>(set, p), InvalidInput);
  p.contact_friction = std::nan("");
  CHECK_THROWS_AS(ElasticSolver<2>(set, p), InvalidInput);
  p.contact_friction = 0.3;
  struct Frictionless : SolidDefaults<2> {
    using contact = NoContact;
  };
  using FrictionlessSolver = ElasticSolver<2, Frictionless>;
  CHECK_THROWS_WITH_AS(FrictionlessSolver(set, p), doctest::Contains("no friction"), InvalidInput);
  CHECK_NOTHROW(ElasticSolver<2>(set, p));
}

}  // TEST_SUITE
