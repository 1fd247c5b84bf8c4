// SPDX-License-Identifier: BSD-3-Clause
#include <doctest/doctest.h>

#include "mpsfsi/kernels/weight.hpp"
#include "mpsfsi/scenes/solid_block.hpp"
#include "mpsfsi/solid/bonds.hpp"

using namespace mpsfsi;

TEST_SUITE("solid") {

TEST_CASE("solid.bonds: symmetric bonds within re of the same body, with reverse links") {
  auto set = scenes::material_block<2>(Vec<2>(0, 0), Vec<2>(0.01, 0.006), 0.001);
  std::vector<std::int32_t> body(set.size(), 0);
  for (std::size_t i = 0; i < set.size(); ++i)
    if (set.positions()[i][0] > 0.005) body[i] = 1;
  BondList<2> bonds;
  bonds.build<KoshizukaWeight>(set.positions(), body, 0.0021);
  REQUIRE(bonds.num_particles() == set.size());
  std::size_t checked = 0;
  for (std::size_t i = 0; i < set.size(); ++i) {
    // Brute force: the same pairs.
    std::vector<Index> expect;
    for (std::size_t j = 0; j < set.size(); ++j)
      if (j != i && body[i] == body[j] && (set.positions()[j] - set.positions()[i]).norm() < 0.0021)
        expect.push_back(static_cast<Index>(j));
    REQUIRE(static_cast<std::size_t>(bonds.end(i) - bonds.begin(i)) == expect.size());
    for (Offset b = bonds.begin(i); b < bonds.end(i); ++b) {
      CHECK(bonds.neighbor(b) == expect[static_cast<std::size_t>(b - bonds.begin(i))]);
      const Offset r = bonds.reverse(b);
      CHECK(bonds.neighbor(r) == static_cast<Index>(i));
      CHECK((bonds.r0(b) + bonds.r0(r)).norm() == doctest::Approx(0.0));
      CHECK(bonds.beta(b) == bonds.beta(r));
      ++checked;
    }
  }
  CHECK(checked == bonds.num_bonds());
  // A full interior neighbourhood at re = 2.1 l0 has 12 bonds.
  CHECK(bonds.initial_count(2 * 10 + 2) == 12);
}

TEST_CASE("solid.bonds: a cut removes both directions for good and counts as damage") {
  auto set = scenes::material_block<2>(Vec<2>(0, 0), Vec<2>(0.005, 0.005), 0.001);
  BondList<2> bonds;
  bonds.build<KoshizukaWeight>(set.positions(), std::vector<std::int32_t>(set.size(), 0), 0.0021);
  const std::size_t i = 12;  // the centre particle
  const Offset b = bonds.begin(i);
  const auto j = static_cast<std::size_t>(bonds.neighbor(b));
  CHECK(bonds.bonded(i, static_cast<Index>(j)));
  CHECK(bonds.cut(b));
  CHECK_FALSE(bonds.cut(bonds.reverse(b)));  // already cut
  CHECK_FALSE(bonds.bonded(i, static_cast<Index>(j)));
  CHECK_FALSE(bonds.bonded(j, static_cast<Index>(i)));
  CHECK(bonds.beta(b) == 0);
  CHECK(bonds.beta(bonds.reverse(b)) == 0);
  CHECK(bonds.num_cut() == 1);
  CHECK(bonds.damage(i) == doctest::Approx(1.0 / 12));
  CHECK(bonds.intact_count(j) == bonds.initial_count(j) - 1);
}

TEST_CASE("solid.bonds: coincident particles of one body are an error") {
  ParticleSet<2> set;
  set.add(Vec<2>(0, 0));
  set.add(Vec<2>(0, 0));
  BondList<2> bonds;
  CHECK_THROWS_WITH_AS(bonds.build<KoshizukaWeight>(set.positions(), std::vector<std::int32_t>(2, 0), 0.0021),
                       doctest::Contains("coincide"), InvalidInput);
}

}
