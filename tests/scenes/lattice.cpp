// SPDX-License-Identifier: BSD-3-Clause
#include <doctest/doctest.h>

#include "mpsfsi/scenes/lattice.hpp"

using namespace mpsfsi;

TEST_SUITE("scenes") {

TEST_CASE_TEMPLATE("scenes.lattice: box counts, spacing and ordering", V, Vec<2>, Vec<3>) {
  constexpr int Dim = static_cast<int>(V::RowsAtCompileTime);
  // 0.1 / 0.01 is 9.999... in binary: the count must still be 11 points per side.
  const auto set = scenes::lattice_box<Dim>(Vec<Dim>::Zero(), Vec<Dim>::Constant(0.1), 0.01, ParticleKind::wall);
  std::size_t expected = 1;
  for (int k = 0; k < Dim; ++k) expected *= 11;
  REQUIRE(set.size() == expected);
  CHECK(set.positions()[1][0] == doctest::Approx(0.01));  // x varies fastest
  CHECK(set.positions()[11][1] == doctest::Approx(0.01));
  CHECK(set.positions().back()[Dim - 1] == doctest::Approx(0.1));
  CHECK(set.kinds()[5] == ParticleKind::wall);
}

TEST_CASE("scenes.lattice: jitter is bounded and repeatable") {
  auto a = scenes::lattice_box<2>(Vec<2>(0, 0), Vec<2>(1, 1), 0.1);
  auto b = a;
  const auto original = a.positions();
  scenes::jitter(a, 0.02, 7);
  scenes::jitter(b, 0.02, 7);
  CHECK(a.positions() == b.positions());
  bool moved = false;
  for (std::size_t i = 0; i < a.size(); ++i) {
    CHECK((a.positions()[i] - original[i]).cwiseAbs().maxCoeff() <= 0.02);
    moved = moved || a.positions()[i] != original[i];
  }
  CHECK(moved);
}

TEST_CASE("scenes.lattice: invalid boxes") {
  CHECK_THROWS_AS(scenes::lattice_box<2>(Vec<2>(0, 0), Vec<2>(1, 1), 0.0), InvalidInput);
  CHECK_THROWS_AS(scenes::lattice_box<2>(Vec<2>(1, 0), Vec<2>(0, 1), 0.1), InvalidInput);
}

}  // TEST_SUITE
