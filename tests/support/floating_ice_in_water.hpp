// SPDX-License-Identifier: BSD-3-Clause
#pragma once

#include "mpsfsi/fluid/fluid_parameters.hpp"
#include "mpsfsi/scenes/floating_ice_beam.hpp"
#include "mpsfsi/solid/solid_parameters.hpp"

namespace mpsfsi::test {

// The floating beam's ice: scenes::FloatingIceBeam's material in plane stress, its inertia scaled by
// `inertia_scale` and its gravity by the inverse (the weight stays), with the brittle solid's bond
// viscosity (solid_parameters.hpp): without it the scaled ice's own vibrations, a few coupling steps
// long at large inertias, grow under the lagging load as well.
inline SolidParameters<2> floating_ice_parameters(const scenes::FloatingIceBeam& scene, double l0,
                                                  double inertia_scale) {
  SolidParameters<2> sp;
  sp.l0 = l0;
  sp.density = scene.ice_density * inertia_scale;
  sp.gravity = Vec<2>(0, -scene.gravity / inertia_scale);
  sp.youngs_modulus = scene.youngs_modulus;
  sp.poisson_ratio = scene.poisson_ratio;
  sp.plane_model = PlaneModel::plane_stress;
  sp.bond_viscosity = SolidParameters<2>::fracture_bond_viscosity;
  return sp;
}

// The water under the floating beam: the settings for water under a structure (docs/theory.md,
// section 2.9) with negative pressures kept.
inline FluidParameters<2> water_under_ice_parameters(double l0, double dt) {
  FluidParameters<2> fp;
  fp.l0 = l0;
  fp.dt = dt;
  fp.wall_condition = WallCondition::neumann;
  fp.density_term_compression_only = false;
  fp.negative_pressure = NegativePressure::keep;
  return fp;
}

}  // namespace mpsfsi::test
