// SPDX-License-Identifier: BSD-3-Clause
#pragma once

#include <cmath>
#include <cstdint>
#include <vector>

#include "mpsfsi/core/abi.hpp"
#include "mpsfsi/core/particle_set.hpp"
#include "mpsfsi/scenes/solid_block.hpp"

namespace mpsfsi {
inline namespace MPSFSI_ABI {
namespace scenes {

// The oscillating clamped plate of Gray, Monaghan & Swift (2001): a plate of length L and
// thickness H sticking out of a clamp at x = 0, started with the first cantilever mode shape
// as velocity profile, tip speed vf c0, c0 = sqrt(E / (3 (1 - 2 nu) rho)).
struct OscillatingPlate {
  double length = 0.2, thickness = 0.02, width = 0.02;  // width only in 3D
  double youngs_modulus = 2.0e6, poisson_ratio = 0.3975, density = 1000;
  double vf = 0.01;                                     // tip speed / c0
  static constexpr double kl = 1.875104069;             // first root of cos kL cosh kL = -1

  double c0() const { return std::sqrt(youngs_modulus / (3 * (1 - 2 * poisson_ratio) * density)); }

  // Analytic first-mode period, Euler-Bernoulli: omega^2 = E H^2 k^4 / (12 rho (1 - nu^2)) in
  // plane strain; without the 1/(1 - nu^2) for a 3D bar (and 2D plane stress).
  double period(bool plane_strain) const {
    const double k = kl / length;
    const double factor = plane_strain ? 1 / (1 - poisson_ratio * poisson_ratio) : 1.0;
    return 2 * M_PI / std::sqrt(youngs_modulus * thickness * thickness * std::pow(k, 4) * factor / (12 * density));
  }

  // Copies the plate's material (density, E, nu) into solver parameters (any type with those
  // members, e.g. SolidParameters), so that cases built on the plate cannot disagree on it.
  template <class Parameters>
  void set_material(Parameters& p) const {
    p.density = density;
    p.youngs_modulus = youngs_modulus;
    p.poisson_ratio = poisson_ratio;
  }

  // Mode shape normalised to 1 at the tip (x from the clamp).
  double mode(double x) const {
    const double k = kl / length, kL = kl;
    const double m = std::sin(kL) + std::sinh(kL), n = std::cos(kL) + std::cosh(kL);
    const double q = 2 * (std::cos(kL) * std::sinh(kL) - std::sin(kL) * std::cosh(kL));
    return (m * (std::cos(k * x) - std::cosh(k * x)) - n * (std::sin(k * x) - std::sinh(k * x))) / q;
  }

  // Particles of the plate and its clamp (clamp_columns of particles at x < 0), the clamped ones
  // listed in `clamped`, the initial velocity set; `tip` is the particle nearest the tip centre.
  template <int Dim>
  ParticleSet<Dim> particles(double l0, int clamp_columns, std::vector<std::size_t>& clamped, std::size_t& tip) const {
    Vec<Dim> lower = Vec<Dim>::Zero(), upper = Vec<Dim>::Zero();
    lower[0] = -clamp_columns * l0;
    upper[0] = length;
    lower[1] = -thickness / 2;
    upper[1] = thickness / 2;
    if constexpr (Dim == 3) {
      lower[2] = -width / 2;
      upper[2] = width / 2;
    }
    ParticleSet<Dim> set = material_block<Dim>(lower, upper, l0);
    clamped = select(set, [](const Vec<Dim>& p) { return p[0] < 0; });
    Vec<Dim> tip_point = Vec<Dim>::Zero();
    tip_point[0] = length;
    tip = 0;
    for (std::size_t i = 0; i < set.size(); ++i) {
      const auto& p = set.positions()[i];
      if (p[0] > 0) set.velocities()[i][1] = vf * c0() * mode(p[0]);
      if ((p - tip_point).norm() < (set.positions()[tip] - tip_point).norm()) tip = i;
    }
    return set;
  }
};

}  // namespace scenes
}  // namespace MPSFSI_ABI
}  // namespace mpsfsi
