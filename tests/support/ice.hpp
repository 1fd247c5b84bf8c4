// SPDX-License-Identifier: BSD-3-Clause
#pragma once

#include "mpsfsi/solid/solid_parameters.hpp"

namespace mpsfsi::test {

// Ice of the paper's case 02 (Table 1: E = 270.084 MPa, sigma_f = 1.140 MPa), nu = 0.3,
// 917 kg/m3, plane stress in 2D: the solid of the fracture unit tests.
template <int Dim>
SolidParameters<Dim> case02_ice(double l0) {
  SolidParameters<Dim> p;
  p.l0 = l0;
  p.density = 917;
  p.youngs_modulus = 270.084e6;
  p.poisson_ratio = 0.3;
  p.plane_model = PlaneModel::plane_stress;
  p.tensile_strength = 1.140e6;
  return p;
}

}  // namespace mpsfsi::test
