// SPDX-License-Identifier: BSD-3-Clause
#include <doctest/doctest.h>

#include <type_traits>

#include "mpsfsi/fluid/water_under_structure.hpp"

using namespace mpsfsi;

TEST_SUITE("fluid") {

TEST_CASE("fluid.water_under_structure: the policies change the surface test and, for long structures, the gradient") {
  static_assert(std::is_same_v<WaterUnderStructure<2>::free_surface, CentroidDeviationSurface<>>);
  static_assert(std::is_same_v<WaterUnderLongStructure<3>::free_surface, CentroidDeviationSurface<>>);
  static_assert(WaterUnderStructure<2>::pressure_gradient_reference == FluidDefaults<2>::pressure_gradient_reference);
  static_assert(WaterUnderLongStructure<2>::pressure_gradient_reference == GradientReference::own_value);
  static_assert(std::is_same_v<WaterUnderLongStructure<3>::linear_solver, FluidDefaults<3>::linear_solver>);
  CHECK(WaterUnderLongStructure<3>::pressure_gradient_reference == GradientReference::own_value);
}

TEST_CASE("fluid.water_under_structure: under_structure sets Neumann walls and the two-way density term, nothing else") {
  FluidParameters<3> p;
  p.l0 = 0.02;
  p.dt = 1e-3;
  p.negative_pressure = NegativePressure::keep;
  REQUIRE(p.wall_condition != WallCondition::neumann);
  REQUIRE(p.density_term_compression_only);
  const auto q = under_structure(p);
  CHECK(q.wall_condition == WallCondition::neumann);
  CHECK_FALSE(q.density_term_compression_only);
  CHECK(q.l0 == p.l0);
  CHECK(q.dt == p.dt);
  CHECK(q.negative_pressure == NegativePressure::keep);
  CHECK(q.density == p.density);
}

}  // TEST_SUITE
