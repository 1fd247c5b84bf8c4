// SPDX-License-Identifier: BSD-3-Clause
#include <doctest/doctest.h>

#include "mpsfsi/scenes/lattice.hpp"
#include "mpsfsi/scenes/tank.hpp"

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

// A tank of 4 x 3 x 2 spacings, one wall layer and one of dummies: walls on every side but the
// top, which is the last axis by default or the one named.
TEST_CASE("scenes.tank: open above along the vertical axis it is given") {
  const double l0 = 1;
  for (const int up : {2, 1, 0}) {
    CAPTURE(up);
    ParticleSet<3> tank;
    scenes::add_tank<3, double>(tank, Vec<3>(4, 3, 2), l0, 1, up);
    const Vec<3> size(4, 3, 2);
    std::size_t below[3] = {0, 0, 0}, beyond[3] = {0, 0, 0}, walls = 0;
    for (std::size_t i = 0; i < tank.size(); ++i) {
      const auto& x = tank.positions()[i];
      for (int k = 0; k < 3; ++k) {
        below[k] += x[k] < 0;
        beyond[k] += x[k] > size[k];
      }
      walls += tank.kinds()[i] == ParticleKind::wall;
      CHECK(!((x.array() > 0).all() && (x.array() < size.array()).all()));  // nothing inside
    }
    for (int k = 0; k < 3; ++k) {
      CHECK(below[k] > 0);
      if (k == up) CHECK(beyond[k] == 0);
      else CHECK(beyond[k] == below[k]);
    }
    // One wall layer around the region's box, less its top face: the box of 6 x 5 x 4 sites
    // (4 x 3 x 2 and a layer on each side), the region's sites and the top face's taken out.
    double top_face = 1;
    for (int k = 0; k < 3; ++k)
      if (k != up) top_face *= size[k] + 2;
    CHECK(walls == static_cast<std::size_t>(6 * 5 * 4 - 4 * 3 * 2 - top_face));
  }
  ParticleSet<2> flat;
  auto vertical_z_in_2d = [&] { scenes::add_tank<2, double>(flat, Vec<2>(1, 1), l0, 1, 2); };
  CHECK_THROWS_AS(vertical_z_in_2d(), InvalidInput);
}

TEST_CASE("scenes.lattice: invalid boxes") {
  CHECK_THROWS_AS(scenes::lattice_box<2>(Vec<2>(0, 0), Vec<2>(1, 1), 0.0), InvalidInput);
  CHECK_THROWS_AS(scenes::lattice_box<2>(Vec<2>(1, 0), Vec<2>(0, 1), 0.1), InvalidInput);
}

}  // TEST_SUITE
