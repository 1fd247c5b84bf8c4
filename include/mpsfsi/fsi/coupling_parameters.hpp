// SPDX-License-Identifier: BSD-3-Clause
#pragma once

#include <cmath>
#include <string>

#include "mpsfsi/core/abi.hpp"
#include "mpsfsi/core/error.hpp"

namespace mpsfsi {
inline namespace MPSFSI_ABI {

// How the interface pressure of eq 18 is read from the fluid particles within re of the interface
// point x_IF (interface_load.hpp; docs/theory.md, section 4.3).
enum class InterfacePressure {
  // Eq 18 as printed: the w-weighted mean of their pressures.
  weighted_mean,
  // The value at x_IF of the w-weighted least-squares plane through their pressures: exact for a
  // pressure linear in space (hydrostatic water), whatever the particles' spacing and offset
  // along the face.
  linear_fit
};

// Settings of FsiCoupler. The fluid's time step is the coupling step; the structure sub-steps
// within it at its own stable step (ElasticSolver::advance_by).
struct CouplingParameters {
  // Radius, in l0, of the weighted averages of eq 18 (interface pressure) and eq 10 (interface
  // acceleration seen by the fluid); the fluid's density radius by default.
  double interface_radius_ratio = 2.1;
  // A structure particle is on the surface (a wall for the fluid, loaded by it) when its
  // number-density gradient exceeds this fraction of n0 (structure_surface.hpp).
  double surface_threshold = 0.1;
  // Eq 10: the interface acceleration as a coupling term in the fluid predictor (the paper's
  // scheme). The wall velocity enters the PPE either way.
  bool interface_acceleration = true;
  // A structure surface particle whose outward site x + l0 n lies inside the tank's fixed walls
  // (the fluid set's own wall and dummy particles, within 0.25 l0) is covered: a dummy particle
  // for the fluid, not loaded (fsi_coupler.hpp). Off: every surface particle is a wall.
  bool covered_surface_as_dummy = true;
  // Scale eq 18's pressure by the wetted fraction of a partially wetted element (interface_load.hpp).
  bool partial_wetting_correction = true;
  // Eq 18's mean, or the linear fit that a floating structure needs: the mean reads the pressure
  // of the water below x_IF, and its wetted fraction drops when the water's particles sit offset
  // along the face (docs/theory.md, section 4.3).
  InterfacePressure interface_pressure = InterfacePressure::weighted_mean;

  void validate() const {
    auto need = [](bool ok, const std::string& what) {
      if (!ok) detail::throw_invalid("CouplingParameters", what);
    };
    need(std::isfinite(interface_radius_ratio) && interface_radius_ratio > 1, "interface_radius_ratio must exceed 1");
    need(surface_threshold > 0 && surface_threshold < 1, "surface_threshold must lie in (0, 1)");
  }
};

}  // namespace MPSFSI_ABI
}  // namespace mpsfsi
