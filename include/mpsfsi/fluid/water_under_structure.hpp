// SPDX-License-Identifier: BSD-3-Clause
// The settings for water held against the underside of a structure (floating ice, a lid) at
// hydrostatic pressure, which docs/theory.md, section 2.9, verifies together: two policy bundles
// for FluidSolver and the parameters that go with them.
#pragma once

#include "mpsfsi/core/abi.hpp"
#include "mpsfsi/fluid/fluid_parameters.hpp"
#include "mpsfsi/fluid/fluid_solver.hpp"
#include "mpsfsi/fluid/free_surface.hpp"
#include "mpsfsi/kernels/gradient.hpp"

namespace mpsfsi {
inline namespace MPSFSI_ABI {

// The centroid-deviation free-surface test in place of the number-density one: it keeps P = 0 off
// the particles that the structure and the walls close (docs/theory.md, section 2.9). Use it with
// under_structure's parameters.
template <int Dim>
struct WaterUnderStructure : FluidDefaults<Dim> {
  using free_surface = CentroidDeviationSurface<>;
};

// The same with the pressure gradient taken about each particle's own pressure (section 1.4):
// the form that keeps water under a structure of more than 150 spacings, such as the floating ice
// beams (section 2.9; docs/validation/fluid.md, water under a structure).
template <int Dim>
struct WaterUnderLongStructure : WaterUnderStructure<Dim> {
  static constexpr GradientReference pressure_gradient_reference = GradientReference::own_value;
};

// `p` with the parameters of water under a structure: Neumann walls (section 2.8) and eq 11's
// density term acting on expansion as well as on compression (section 2.9). The rest of `p` stays.
template <int Dim, class Scalar>
FluidParameters<Dim, Scalar> under_structure(FluidParameters<Dim, Scalar> p) {
  p.wall_condition = WallCondition::neumann;
  p.density_term_compression_only = false;
  return p;
}

}  // namespace MPSFSI_ABI
}  // namespace mpsfsi
