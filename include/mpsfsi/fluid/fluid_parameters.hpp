// SPDX-License-Identifier: BSD-3-Clause
#pragma once

#include <cmath>
#include <string>

#include "mpsfsi/core/abi.hpp"
#include "mpsfsi/core/error.hpp"
#include "mpsfsi/core/types.hpp"

namespace mpsfsi {
inline namespace MPSFSI_ABI {

// What to do with negative pressures after the PPE solve.
enum class NegativePressure { clamp_to_zero, keep };

// What to do with an enclosed region with fluid in it: fluid or wall particles in the PPE,
// connected, none of which touches the free surface, so their pressure level is undetermined (a
// singular PPE). A closed container filled to the top is one (an error: the model needs a free
// surface); fluid trapped between the fragments of a breaking structure is another
// (zero_pressure: left out of the PPE with P = 0, and counted). A region of wall particles only
// (the closed faces of a crack, a wall inside dummies) holds no fluid to get wrong: it is always
// left out with P = 0, under either setting, and not counted.
enum class EnclosedRegion { error, zero_pressure };

// The wall condition of the PPE (docs/theory.md, section 2.8).
//   wall_rows   the paper's: wall particles are unknowns of the PPE with eq 11's source, the
//               divergence of u* taken over fluid and wall neighbours; dummy particles are left
//               out of the PPE. Holds water on a floor, but water under a ceiling (the underside
//               of a floating body) parts from it.
//   neumann     dummy particles enter every row's Laplacian with a ghost pressure, the row's own
//               pressure extended along the wall's Neumann condition
//               grad P = rho g_t + (rho/dt) ((u*_f - u_wall) . n) n  (n towards the dummies),
//               the divergence of u* is taken over fluid neighbours only, and wall rows have
//               no divergence source: the impermeability comes from the ghosts alone.
enum class WallCondition { wall_rows, neumann };

// Physical and numerical parameters of FluidSolver. Lengths in m, times in s, SI throughout.
// Radii are given as multiples of l0 (docs/theory.md, section 1.2: KO96 use 2.1 l0 for density and
// gradient, 4.0 l0 for the Laplacian; a widely used open code 2.1 / 3.1).
template <int Dim, class Scalar = double>
struct FluidParameters {
  Scalar l0 = 0;                       // initial particle spacing (required)
  Scalar density = 1000;               // rho
  Scalar kinematic_viscosity = 1e-6;   // nu
  Vec<Dim, Scalar> gravity = gravity_default();
  Scalar re_density_ratio = Scalar(2.1);    // number density: free surface, eq 11's density term
  Scalar re_gradient_ratio = Scalar(2.1);   // pressure gradient and divergence of u*
  Scalar re_laplacian_ratio = Scalar(3.1);  // viscosity and PPE
  Scalar gamma = Scalar(0.03);              // PPE blending, eq 11 (Lee et al. 2011)
  // Apply eq 11's density term only where the fluid is compressed (n > n0). Particles just
  // below a free surface lack the neighbours above them, so their n is ~1 % below n0 at rest;
  // the full term turns that into a spurious pressure dip of about half a row's hydrostatic
  // increment (it scales as 1/dt^2), which draws particles together under the surface and
  // drives them unstable (seen in the hydrostatic tank).
  bool density_term_compression_only = true;
  Scalar surface_beta = Scalar(0.97);       // free surface where n < beta n0
  WallCondition wall_condition = WallCondition::wall_rows;
  NegativePressure negative_pressure = NegativePressure::clamp_to_zero;
  EnclosedRegion enclosed_region = EnclosedRegion::error;
  // Time step: fixed when dt > 0, else automatic from the limits below, capped at max_dt when
  // max_dt > 0 (a coupled structure or an output cadence may need shorter steps than the fluid:
  // from rest the Courant limit alone allows steps of several ms).
  Scalar dt = 0;
  Scalar max_dt = 0;
  Scalar courant = Scalar(0.2);             // dt <= courant l0 / max|u|
  Scalar viscous_number = Scalar(0.2);      // dt <= viscous_number l0^2 / nu
  bool warn_only_on_unstable_dt = false;    // a fixed dt above the limit throws unless set
  // PPE linear solve: relative residual and iteration cap.
  Scalar ppe_tolerance = Scalar(1e-8);
  int ppe_max_iterations = 5000;
  // A blow-up is declared when a fluid speed exceeds this multiple of sqrt(2 |g| H_ref) or
  // l0/dt (whichever is larger), H_ref being the initial height of the particle set.
  Scalar blowup_speed_factor = Scalar(10);

  static Vec<Dim, Scalar> gravity_default() {
    Vec<Dim, Scalar> g = Vec<Dim, Scalar>::Zero();
    g[Dim - 1] = Scalar(-9.81);
    return g;
  }

  Scalar re_density() const { return re_density_ratio * l0; }
  Scalar re_gradient() const { return re_gradient_ratio * l0; }
  Scalar re_laplacian() const { return re_laplacian_ratio * l0; }

  // Throws InvalidInput naming the first parameter that is missing or out of range.
  void validate() const {
    auto need = [](bool ok, const std::string& what) {
      if (!ok) detail::throw_invalid("FluidParameters", what);
    };
    need(std::isfinite(l0) && l0 > 0, "l0 (particle spacing) must be set and positive");
    need(std::isfinite(density) && density > 0, "density must be positive");
    need(std::isfinite(kinematic_viscosity) && kinematic_viscosity >= 0, "kinematic_viscosity must be >= 0");
    need(gravity.allFinite(), "gravity must be finite");
    need(re_density_ratio > 1 && re_gradient_ratio > 1 && re_laplacian_ratio > 1, "effective radii must exceed l0");
    need(gamma >= 0 && gamma <= 1, "gamma must lie in [0, 1]");
    need(surface_beta > 0 && surface_beta < 1, "surface_beta must lie in (0, 1)");
    need(std::isfinite(dt) && dt >= 0, "dt must be >= 0 (0 selects the automatic step)");
    need(std::isfinite(max_dt) && max_dt >= 0, "max_dt must be >= 0 (0: the automatic step is not capped)");
    need(courant > 0 && courant <= 1, "courant must lie in (0, 1]");
    need(viscous_number > 0, "viscous_number must be positive");
    need(ppe_tolerance > 0 && ppe_tolerance < 1, "ppe_tolerance must lie in (0, 1)");
    need(ppe_max_iterations > 0, "ppe_max_iterations must be positive");
  }
};

}  // namespace MPSFSI_ABI
}  // namespace mpsfsi
