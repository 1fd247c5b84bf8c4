// SPDX-License-Identifier: BSD-3-Clause
#pragma once

#include "mpsfsi/fluid/fluid_solver.hpp"

namespace mpsfsi::test {

// The fluid policies of the settings for water under a structure (docs/theory.md, section 2.9):
// CentroidDeviationSurface in place of the default free-surface test. The verification cases pair
// them with Neumann walls and the full density term, which are parameters, not policies.
template <int Dim>
struct WaterUnderStructurePolicies : FluidDefaults<Dim> {
  using free_surface = CentroidDeviationSurface<>;
};

// The same with the pressure gradient taken about each particle's own pressure, the form that
// keeps water under a long lid longest (docs/theory.md, section 2.9).
template <int Dim>
struct OwnValueGradientPolicies : WaterUnderStructurePolicies<Dim> {
  static constexpr GradientReference pressure_gradient_reference = GradientReference::own_value;
};

}  // namespace mpsfsi::test
