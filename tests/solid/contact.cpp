// SPDX-License-Identifier: BSD-3-Clause
#include <doctest/doctest.h>

#include "mpsfsi/scenes/solid_block.hpp"
#include "mpsfsi/solid/elastic_solver.hpp"

using namespace mpsfsi;

TEST_SUITE("solid") {

TEST_CASE("solid.contact: two bodies collide, repel and never interpenetrate; momentum is conserved") {
  const double l0 = 0.01;
  auto set = scenes::material_block<2>(Vec<2>(0, 0), Vec<2>(0.05, 0.05), l0);
  const std::size_t first_b = scenes::append(set, scenes::material_block<2>(Vec<2>(0.06, 0), Vec<2>(0.11, 0.05), l0));
  std::vector<std::int32_t> body(set.size(), 0);
  for (std::size_t i = first_b; i < set.size(); ++i) body[i] = 1;
  for (std::size_t i = 0; i < first_b; ++i) set.velocities()[i] = Vec<2>(2.0, 0);
  SolidParameters<2> p;
  p.l0 = l0;
  p.density = 1000;
  p.youngs_modulus = 1e6;
  p.poisson_ratio = 0.3;
  ElasticSolver<2> s(set, p, body);
  // No bond joins the bodies.
  for (std::size_t i = 0; i < first_b; ++i)
    for (Offset b = s.bonds().begin(i); b < s.bonds().end(i); ++b) CHECK(body[static_cast<std::size_t>(s.bonds().neighbor(b))] == 0);
  auto momentum = [&] {
    Vec<2> m = Vec<2>::Zero();
    for (const auto& v : s.particles().velocities()) m += s.particle_mass() * v;
    return m;
  };
  const Vec<2> m0 = momentum();
  double closest = 1;
  std::size_t touching = 0;
  while (s.time() < 0.02) {
    s.step();
    touching = std::max(touching, s.contact().active_pairs());
    for (std::size_t i = 0; i < first_b; ++i)
      for (std::size_t j = first_b; j < set.size(); ++j)
        closest = std::min(closest, (s.particles().positions()[i] - s.particles().positions()[j]).norm());
  }
  CHECK(touching > 0);
  CHECK(closest > 0.5 * l0);
  double vb = 0;
  for (std::size_t j = first_b; j < set.size(); ++j) vb += s.particles().velocities()[j][0];
  CHECK(vb / static_cast<double>(set.size() - first_b) > 0.5);  // the struck body moves off
  CHECK((momentum() - m0).norm() < 1e-9 * m0.norm());
}

TEST_CASE("solid.contact: NoContact lets bodies pass through each other") {
  struct Policies : SolidDefaults<2> {
    using contact = NoContact;
  };
  const double l0 = 0.01;
  auto set = scenes::material_block<2>(Vec<2>(0, 0), Vec<2>(0.03, 0.03), l0);
  const std::size_t first_b = scenes::append(set, scenes::material_block<2>(Vec<2>(0.04, 0), Vec<2>(0.07, 0.03), l0));
  std::vector<std::int32_t> body(set.size(), 0);
  for (std::size_t i = first_b; i < set.size(); ++i) body[i] = 1;
  for (std::size_t i = 0; i < first_b; ++i) set.velocities()[i] = Vec<2>(2.0, 0);
  SolidParameters<2> p;
  p.l0 = l0;
  p.density = 1000;
  p.youngs_modulus = 1e6;
  p.poisson_ratio = 0.3;
  ElasticSolver<2, Policies> s(set, p, body);
  s.advance_to(0.03);
  CHECK(s.particles().positions()[0][0] > 0.055);  // the leading body has moved through
}

}
