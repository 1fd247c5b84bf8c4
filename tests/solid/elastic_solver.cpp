// SPDX-License-Identifier: BSD-3-Clause
#include <doctest/doctest.h>

#include <cmath>
#include <string>

#include "mpsfsi/scenes/solid_block.hpp"
#include "mpsfsi/solid/elastic_solver.hpp"

using namespace mpsfsi;

namespace {

SolidParameters<2> rubber(double l0 = 0.01) {
  SolidParameters<2> p;
  p.l0 = l0;
  p.density = 1000;
  p.youngs_modulus = 1e6;
  p.poisson_ratio = 0.3;
  return p;
}

ParticleSet<2> block(double w = 0.06, double h = 0.04, double l0 = 0.01) {
  return scenes::material_block<2>(Vec<2>(0, 0), Vec<2>(w, h), l0);
}

}  // namespace

TEST_SUITE("solid") {

TEST_CASE("solid.elastic_solver: bad input gets a clear error") {
  SUBCASE("empty set") {
    CHECK_THROWS_WITH_AS(ElasticSolver<2>(ParticleSet<2>{}, rubber()), doctest::Contains("empty"), InvalidInput);
  }
  SUBCASE("missing Young's modulus") {
    auto p = rubber();
    p.youngs_modulus = 0;
    CHECK_THROWS_WITH_AS(ElasticSolver<2>(block(), p), doctest::Contains("youngs_modulus"), InvalidInput);
  }
  SUBCASE("missing Poisson ratio") {
    auto p = rubber();
    p.poisson_ratio = -2;
    CHECK_THROWS_WITH_AS(ElasticSolver<2>(block(), p), doctest::Contains("poisson_ratio"), InvalidInput);
  }
  SUBCASE("missing density") {
    auto p = rubber();
    p.density = 0;
    CHECK_THROWS_WITH_AS(ElasticSolver<2>(block(), p), doctest::Contains("density"), InvalidInput);
  }
  SUBCASE("overlapping particles") {
    auto set = block();
    set.add(set.positions()[4] + Vec<2>(0.001, 0));
    CHECK_THROWS_WITH_AS(ElasticSolver<2>(std::move(set), rubber()), doctest::Contains("overlap"), InvalidInput);
  }
  SUBCASE("NaN position") {
    auto set = block();
    set.positions()[2][1] = std::nan("");
    CHECK_THROWS_AS(ElasticSolver<2>(std::move(set), rubber()), InvalidInput);
  }
  SUBCASE("time step above the stability limit") {
    auto p = rubber();
    p.dt = 2 * p.max_stable_dt();
    CHECK_THROWS_WITH_AS(ElasticSolver<2>(block(), p), doctest::Contains("stability limit"), InvalidInput);
    ElasticSolver<2> ok(block(), rubber());
    CHECK_THROWS_WITH_AS(ok.step(2 * rubber().max_stable_dt()), doctest::Contains("stability limit"), InvalidInput);
  }
  SUBCASE("wrong number of body ids") {
    CHECK_THROWS_WITH_AS(ElasticSolver<2>(block(), rubber(), std::vector<std::int32_t>(3, 0)),
                         doctest::Contains("body ids"), InvalidInput);
  }
  SUBCASE("particles spaced differently from l0") {
    // 1 mm apart with l0 = 2 mm would make every mass rho l0^2 four times too large.
    CHECK_THROWS_WITH_AS(ElasticSolver<2>(block(0.06, 0.04, 0.001), rubber(0.002)),
                         doctest::Contains("m apart (median distance to the nearest neighbour) but l0 = 0.002 m"),
                         InvalidInput);
    CHECK_THROWS_WITH_AS(ElasticSolver<2>(block(0.06, 0.04, 0.02), rubber(0.01)),
                         doctest::Contains("spaced more widely than l0"), InvalidInput);
    CHECK_NOTHROW(ElasticSolver<2>(block(0.06, 0.04, 0.001), rubber(0.001)));
  }
  SUBCASE("non-finite external force") {
    ElasticSolver<2> s(block(), rubber());
    s.external_force()[7] = Vec<2>(std::nan(""), 0);
    CHECK_THROWS_WITH_AS(s.step(), doctest::Contains("external force on particle 7 (id 7) is not finite"),
                         InvalidInput);
    CHECK(s.step_count() == 0);
  }
  SUBCASE("times in messages keep their significant digits") {
    auto p = rubber();
    p.youngs_modulus = 1e12;  // a limit of a few 1e-7 s, which fixed decimals print as 0.000000
    p.dt = 1e-6;
    std::string message;
    try {
      ElasticSolver<2> s(block(), p);
    } catch (const InvalidInput& e) {
      message = e.what();
    }
    CHECK(message.find("dt = 1e-06 s exceeds the stability limit " + detail::format_number(p.max_stable_dt()) +
                       " s") != std::string::npos);
    CHECK(p.max_stable_dt() < 1e-6);
    CHECK(message.find("0.000000") == std::string::npos);
  }
  SUBCASE("bad boundary conditions") {
    ElasticSolver<2> s(block(), rubber());
    CHECK_THROWS_WITH_AS(s.clamp(1000), doctest::Contains("ElasticSolver::clamp: particle 1000 out of range"),
                         InvalidInput);
    CHECK_THROWS_WITH_AS(s.support(0, Vec<2>::Zero()), doctest::Contains("normal"), InvalidInput);
  }
}

TEST_CASE("solid.elastic_solver: automatic dt from the P-wave speed") {
  const auto p = rubber();
  ElasticSolver<2> s(block(), p);
  const auto lame = p.lame();
  const double c = std::sqrt((lame.lambda + 2 * lame.mu) / p.density);
  CHECK(s.dt() == doctest::Approx(p.courant * p.l0 / c));
  auto stress = p;
  stress.plane_model = PlaneModel::plane_stress;
  CHECK(stress.p_wave_speed() == doctest::Approx(std::sqrt(p.youngs_modulus / (1 - 0.09) / p.density)));
}

TEST_CASE("solid.elastic_solver: a free body falls freely, unstressed") {
  auto p = rubber();
  p.gravity = Vec<2>(0, -9.81);
  ElasticSolver<2> s(block(), p);
  const Vec<2> x0 = s.particles().positions()[5];
  s.advance_to(0.05);
  const double t = s.time();
  CHECK(s.particles().positions()[5][1] - x0[1] == doctest::Approx(-0.5 * 9.81 * t * t).epsilon(1e-9));
  for (const auto& sigma : s.stresses()) CHECK(sigma.norm() < 1e-6 * p.youngs_modulus);
}

TEST_CASE("solid.elastic_solver: clamped, prescribed and supported particles obey their constraints") {
  auto p = rubber();
  p.gravity = Vec<2>(0, -9.81);
  ElasticSolver<2> s(block(), p);
  s.clamp(0);
  s.prescribe_velocity(5, Vec<2>(0.01, 0));
  s.support(2, Vec<2>(0, 1));
  const Vec<2> x0 = s.particles().positions()[0], x5 = s.particles().positions()[5], x2 = s.particles().positions()[2];
  for (int k = 0; k < 200; ++k) s.step();
  CHECK((s.particles().positions()[0] - x0).norm() == 0);
  CHECK((s.particles().positions()[5] - x5 - Vec<2>(0.01 * s.time(), 0)).norm() < 1e-12);
  CHECK(s.particles().positions()[2][1] == x2[1]);
  CHECK(s.reaction(0).norm() > 0);
  CHECK(s.reaction(2)[0] == 0);                   // a support only pushes along its normal
  CHECK(s.reaction(7).norm() == 0);               // a free particle has none
  s.release(5);
  CHECK(s.constraint(5) == Constraint::free);
}

TEST_CASE("solid.elastic_solver: a blow-up is reported with step, time and particle; the state is kept") {
  auto p = rubber();
  p.dt = p.max_stable_dt();
  ElasticSolver<2> s(block(), p);
  s.external_force()[3] = Vec<2>(1e9, 0);
  bool thrown = false;
  VecArray<2> last;
  try {
    for (int k = 0; k < 100; ++k) {
      last = s.particles().positions();
      s.step();
    }
  } catch (const SimulationError& e) {
    thrown = true;
    CHECK(e.step() == s.step_count() + 1);
    CHECK(e.particle() >= 0);
    CHECK(std::string(e.what()).find("blow-up") != std::string::npos);
    CHECK(s.particles().positions() == last);
  }
  CHECK(thrown);
}

TEST_CASE("solid.elastic_solver: a body moving rigidly faster than its P-wave speed is not a blow-up") {
  const auto p = rubber();
  auto set = block();
  const Vec<2> fast(3 * p.p_wave_speed(), 0);
  for (auto& v : set.velocities()) v = fast;
  ElasticSolver<2> s(std::move(set), p);
  const Vec<2> x0 = s.particles().positions()[5];
  for (int k = 0; k < 50; ++k) s.step();
  CHECK((s.particles().positions()[5] - x0 - s.time() * fast).norm() < 1e-9 * fast.norm() * s.time());
  for (const auto& sigma : s.stresses()) CHECK(sigma.norm() < 1e-6 * p.youngs_modulus);
}

TEST_CASE("solid.elastic_solver: advance_by sub-steps a fluid step exactly") {
  ElasticSolver<2> s(block(), rubber());
  const double dt = s.dt();
  CHECK(s.advance_by(3.5 * dt) == 4);
  CHECK(s.time() == doctest::Approx(3.5 * dt));
  CHECK(s.last_dt() == doctest::Approx(3.5 * dt / 4));
}

TEST_CASE("solid.elastic_solver: output fields carry displacement, stress and damage") {
  ElasticSolver<2> s(block(), rubber());
  s.prescribe_velocity(0, Vec<2>(-0.1, 0));
  for (int k = 0; k < 20; ++k) s.step();
  const auto& out = s.output();
  std::vector<std::string> names;
  out.for_each_vector_field([&](const std::string& name, const auto&) { names.push_back(name); });
  out.for_each_tensor_field([&](const std::string& name, const auto&) { names.push_back(name); });
  out.for_each_scalar_field([&](const std::string& name, const auto&) { names.push_back(name); });
  for (const char* want : {"displacement", "stress", "damage"})
    CHECK(std::find(names.begin(), names.end(), want) != names.end());
}

}
