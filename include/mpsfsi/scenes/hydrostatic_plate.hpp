// SPDX-License-Identifier: BSD-3-Clause
#pragma once

#include <cmath>
#include <cstdint>
#include <vector>

#include "mpsfsi/core/abi.hpp"
#include "mpsfsi/core/error.hpp"
#include "mpsfsi/core/particle_set.hpp"
#include "mpsfsi/scenes/solid_block.hpp"
#include "mpsfsi/scenes/tank.hpp"

namespace mpsfsi {
inline namespace MPSFSI_ABI {
namespace scenes {

// Hydrostatic water column on a clamped elastic plate (Fourey et al. 2017; Khayyer et al. 2018),
// 2D: water `span` wide and `water_height` high between two rigid side walls; its bottom is an
// aluminium plate of the same span and thickness `thickness`, both ends clamped. The plate
// continues `clamp_columns` columns into each wall, and those particles are clamped, so the clamp
// faces are at x = 0 and x = span. Analytic mid-span deflection (Euler-Bernoulli, plane strain):
//   w = q L^4 / (384 D),  D = E e^3 / (12 (1 - nu^2)),  q = rho_f g H (+ rho_s g e with the
//   plate's own weight): 6.43e-5 m and 6.86e-5 m.
struct HydrostaticPlate {
  double span = 1.0, water_height = 2.0, thickness = 0.05;
  double fluid_density = 1000, gravity = 9.81;
  double youngs_modulus = 67.5e9, poisson_ratio = 0.34, density = 2700;
  // Also the side walls' thickness in layers (one wall, the rest dummy). 5, not 3: the plate's end
  // faces are structure surface, free-surface (P = 0) rows of the PPE; at 3 layers they are within
  // the Laplacian's 3.1 l0 of the corner wall particles, lower their pressure and draw the corner
  // water in (peak corner speed at h/l0 = 8 without the covered-surface rule: 0.40 m/s at 3
  // layers, 0.28 at 5; the rule brings the latter to 0.06, docs/validation/fsi.md).
  int clamp_columns = 5;

  double flexural_rigidity() const {
    return youngs_modulus * std::pow(thickness, 3) / (12 * (1 - poisson_ratio * poisson_ratio));
  }
  // Mid-span deflection (positive down) under the water only, or with the plate's weight too.
  double deflection(bool with_plate_weight) const {
    const double q = fluid_density * gravity * water_height + (with_plate_weight ? density * gravity * thickness : 0);
    return q * std::pow(span, 4) / (384 * flexural_rigidity());
  }

  // The exact hydrostatic load rho_f g H as external forces on the plate's top row between the
  // clamps (one surface element l0 each): the plate alone under what the water should apply.
  template <class Solid>
  void apply_water_load(Solid& plate, double l0) const {
    const double q = fluid_density * gravity * water_height;
    const auto& x = plate.particles().positions();
    for (std::size_t i = 0; i < x.size(); ++i)
      if (x[i][1] > -l0 && x[i][0] > 0 && x[i][0] < span) plate.external_force()[i] = Vec<2>(0, -q * l0);
  }

  template <class Parameters>
  void set_material(Parameters& p) const {
    p.density = density;
    p.youngs_modulus = youngs_modulus;
    p.poisson_ratio = poisson_ratio;
  }

  // The water and the two side walls (wall layer against the water, dummies behind), up to
  // `wall_height` (default: the water height plus four spacings).
  ParticleSet<2> fluid_particles(double l0, double wall_height = 0) const {
    check(l0);
    if (wall_height <= 0) wall_height = water_height + 4 * l0;
    auto set = lattice_region(0, span, 0, water_height, l0, ParticleKind::fluid);
    const double depth = clamp_columns * l0;
    for (const double x0 : {-depth, span}) {
      auto wall = lattice_region(x0, x0 + depth, 0, wall_height, l0, ParticleKind::dummy);
      for (std::size_t i = 0; i < wall.size(); ++i) {
        const double x = wall.positions()[i][0];
        if (std::abs(x - (x0 < 0 ? -l0 / 2 : span + l0 / 2)) < l0 / 4) wall.kinds()[i] = ParticleKind::wall;
      }
      append(set, wall);
    }
    return set;
  }

  // The plate, y in [-thickness, 0], x in [-clamp_columns l0, span + clamp_columns l0]; the
  // particles outside [0, span] are listed in `clamped`, `middle` is the top-surface particle
  // nearest mid-span.
  ParticleSet<2> plate_particles(double l0, std::vector<std::size_t>& clamped, std::size_t& middle) const {
    check(l0);
    auto set = material_block<2>(Vec<2>(-clamp_columns * l0, -thickness),
                                 Vec<2>(span + clamp_columns * l0, 0.0), l0);
    clamped = select(set, [&](const Vec<2>& x) { return x[0] < 0 || x[0] > span; });
    middle = 0;
    double best = 1e300;
    for (std::size_t i = 0; i < set.size(); ++i) {
      const double d = std::abs(set.positions()[i][0] - span / 2) + std::abs(set.positions()[i][1] + l0 / 2);
      if (d < best) best = d, middle = i;
    }
    return set;
  }

 private:
  void check(double l0) const {
    if (!(l0 > 0) || !(thickness >= 2 * l0))
      detail::throw_invalid("scenes::HydrostaticPlate", "l0 must be positive and at most half the plate thickness");
  }
  static ParticleSet<2> lattice_region(double x0, double x1, double y0, double y1, double l0, ParticleKind kind) {
    ParticleSet<2> set;
    add_block(set, Vec<2>(x0, y0), Vec<2>(x1, y1), l0, kind);
    return set;
  }
};

}  // namespace scenes
}  // namespace MPSFSI_ABI
}  // namespace mpsfsi
