// SPDX-License-Identifier: BSD-3-Clause
#include <doctest/doctest.h>

#include "mpsfsi/scenes/oscillating_plate.hpp"
#include "mpsfsi/scenes/solid_block.hpp"

using namespace mpsfsi;

TEST_SUITE("scenes") {

TEST_CASE("scenes.solid_block: one particle per cell, at the cell centres") {
  const auto set = scenes::material_block<2>(Vec<2>(0, 0), Vec<2>(0.2, 0.02), 0.002);
  CHECK(set.size() == 100 * 10);
  CHECK(set.positions()[0].isApprox(Vec<2>(0.001, 0.001)));
  CHECK(set.kinds()[0] == ParticleKind::solid);
  const auto cube = scenes::material_block<3>(Vec<3>::Zero(), Vec<3>(0.01, 0.02, 0.03), 0.01);
  CHECK(cube.size() == 6);
  CHECK_THROWS_WITH_AS(scenes::material_block<2>(Vec<2>(0, 0), Vec<2>(0.015, 0.02), 0.01),
                       doctest::Contains("whole number"), InvalidInput);
  const auto top = scenes::select(set, [](const Vec<2>& p) { return p[1] > 0.018; });
  CHECK(top.size() == 100);
}

TEST_CASE("scenes.oscillating_plate: mode shape and period of Gray, Monaghan & Swift (2001)") {
  scenes::OscillatingPlate plate;
  CHECK(plate.mode(plate.length) == doctest::Approx(1.0).epsilon(1e-9));
  CHECK(plate.mode(0) == doctest::Approx(0.0));
  // Reference values worked by hand from the formulas of Gray, Monaghan & Swift (2001) for
  // E = 2 MPa, nu = 0.3975, rho = 1000 kg/m3: c0 = sqrt(E / (3 (1 - 2 nu) rho)), and the
  // plane-strain thin-plate period (docs/validation/solid.md).
  CHECK(plate.c0() == doctest::Approx(57.0266).epsilon(1e-5));
  CHECK(plate.period(true) == doctest::Approx(0.25403).epsilon(1e-4));
  std::vector<std::size_t> clamped;
  std::size_t tip = 0;
  const auto set = plate.particles<2>(0.002, 4, clamped, tip);
  CHECK(clamped.size() == 4 * 10);
  CHECK(set.velocities()[tip][1] == doctest::Approx(plate.vf * plate.c0()).epsilon(0.01));
}

}
