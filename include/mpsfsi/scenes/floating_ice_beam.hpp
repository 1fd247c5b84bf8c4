// SPDX-License-Identifier: BSD-3-Clause
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <vector>

#include "mpsfsi/core/abi.hpp"
#include "mpsfsi/core/error.hpp"
#include "mpsfsi/core/particle_set.hpp"
#include "mpsfsi/scenes/solid_block.hpp"
#include "mpsfsi/scenes/tank.hpp"

namespace mpsfsi {
inline namespace MPSFSI_ABI {
namespace scenes {

// A long ice beam floating freely on water in a 2D tank, loaded at its left end by a vertical
// force P per unit width (docs/validation/fsi.md, open problems: water under a long structure). The water is the beam's
// elastic foundation, k = rho_w g; a beam longer than a few 1/lambda behaves as semi-infinite, and
// Hetenyi's solution (Beams on Elastic Foundation, 1946, section on the semi-infinite beam with
// an end load) gives, with D the flexural rigidity per unit width and x from the loaded end:
//   lambda = (k / (4 D))^(1/4),
//   w(x)   = (2 P lambda / k) e^(-lambda x) cos(lambda x)        (downwards),
//   M(x)   = -(P / lambda) e^(-lambda x) sin(lambda x),         largest at x = pi / (4 lambda),
// where the top fibre is in tension; the beam fails where 6 |M| / h^2 reaches sigma_f:
//   P_f = sigma_f h^2 lambda / (6 e^(-pi/4) sin(pi/4)) = 0.68 sigma_f (rho_w g h^5 / E)^(1/4)
// (with D = E h^3 / 12), the breaking term of Croasdale's load on a sloping structure.
//
// Layout (y up): the tank's floor at y = 0, its left wall at x = 0; the beam [0, beam_length] x
// [y_b, y_b + h] with its loaded end face against the left wall (the wall keeps the water off the
// loaded end's top: with water beside it the end would be flooded once it dips below the
// water line, which the foundation model leaves out); water under the beam up to y_b and, beyond
// the far end, open water up to the beam's draft (to the nearest row). The tank is water_length
// long, so the open water is water_length - beam_length.
//
// In 3D (the member functions' Dim = 3) the same section is extruded along z over `width`: the ice
// is a strip across a channel of that width, its long sides against the channel's side walls,
// which, like the end wall, do not hold it. A strip a few thicknesses wide bends as a beam with
// free sides (plane stress, D = E h^3 / 12); all quantities per unit width.
//
// The tank wall does not hold the beam: FsiCoupler has no contact between a structure and the
// tank's fixed walls. The open water pushes on the far end face with rho_w g d^2 / 2 per unit
// width (d the wetted depth of the face) and nothing pushes back on the loaded end, so a free beam
// drifts into the wall. Hold one particle of the loaded end horizontally, a roller on the wall at
// mid-thickness: ElasticSolver::support(roller_particle(...), e_x). Holding the whole end column
// would keep the end face vertical, a guided end (w'(0) = 0) in place of Hetenyi's free one: the
// same equations give it w(0) = P lambda / k, half the free end's, and the largest moment,
// P / (2 lambda), at the end.
struct FloatingIceBeam {
  double thickness = 0.04;          // h, m
  double beam_length = 0;           // m; 0: 5 / lambda rounded up to whole spacings
  double open_water = 0.3;          // m of free surface beyond the far end
  double water_depth = 0.25;        // m of water under the beam
  double youngs_modulus = 60e6;     // Pa
  double poisson_ratio = 0.3;
  double ice_density = 917;         // kg/m3
  double tensile_strength = 30e3;   // sigma_f, Pa
  double water_density = 1000;      // kg/m3
  double gravity = 9.81;            // m/s2
  bool plane_strain = false;        // the plane model of the 2D beam: D = E' h^3 / 12
  double width = 0;                 // 3D: the strip's and the channel's width along z, m

  // E' of the plane model: E in plane stress, E / (1 - nu^2) in plane strain.
  double plane_modulus() const {
    return plane_strain ? youngs_modulus / (1 - poisson_ratio * poisson_ratio) : youngs_modulus;
  }
  double flexural_rigidity() const { return plane_modulus() * std::pow(thickness, 3) / 12; }
  double foundation_modulus() const { return water_density * gravity; }
  double lambda() const { return std::pow(foundation_modulus() / (4 * flexural_rigidity()), 0.25); }
  // Hetenyi's semi-infinite beam under P at x = 0, deflection positive downwards.
  double deflection(double P, double x) const {
    const double l = lambda();
    return 2 * P * l / foundation_modulus() * std::exp(-l * x) * std::cos(l * x);
  }
  double moment(double P, double x) const {
    const double l = lambda();
    return -P / l * std::exp(-l * x) * std::sin(l * x);
  }
  double largest_moment_position() const { return std::acos(-1.0) / (4 * lambda()); }
  // The end load at which the top fibre at x = pi / (4 lambda) reaches sigma_f.
  double failure_load() const {
    const double x = largest_moment_position();
    return tensile_strength * thickness * thickness / (6 * std::abs(moment(1.0, x)));
  }
  double draft() const { return ice_density / water_density * thickness; }

  // Deflection (m, downwards) of each of the beam's columns: the mean over the column's particles of
  // how far each lies below its reference position. Column c counts from the loaded end and is
  // centred at x = (c + 1/2) l0; in 3D it spans the width.
  template <int Dim>
  std::vector<double> column_deflections(const VecArray<Dim, double>& positions, const VecArray<Dim, double>& reference,
                                         double l0) const {
    const auto columns = static_cast<std::size_t>(std::lround(beam_length_for(l0) / l0));
    std::vector<double> w(columns, 0.0);
    std::vector<int> count(columns, 0);
    for (std::size_t i = 0; i < positions.size(); ++i) {
      const auto c = std::min(columns - 1, static_cast<std::size_t>(reference[i][0] / l0));
      w[c] -= positions[i][1] - reference[i][1];
      ++count[c];
    }
    for (std::size_t c = 0; c < columns; ++c)
      if (count[c] > 0) w[c] /= count[c];
    return w;
  }

  // Column deflections (column_deflections) against Hetenyi's under P: the end column's relative
  // error, and the RMS of the difference over the columns with 0 <= x <= 3 / lambda relative to the
  // end column's reference deflection.
  struct ProfileError {
    double end = 0;
    double rms = 0;
  };
  ProfileError profile_error(const std::vector<double>& w, double P, double l0) const {
    if (w.empty() || !(l0 > 0) || !(P != 0))
      detail::throw_invalid("scenes::FloatingIceBeam::profile_error",
                            "needs at least one column deflection, a positive l0 and a non-zero load");
    const double w_end = deflection(P, 0.5 * l0);
    ProfileError e;
    e.end = w[0] / w_end - 1;
    double sum = 0;
    std::size_t n = 0;
    for (; n < w.size() && (n + 0.5) * l0 <= 3 / lambda(); ++n)
      sum += std::pow(w[n] - deflection(P, (n + 0.5) * l0), 2);
    e.rms = std::sqrt(sum / static_cast<double>(n)) / w_end;
    return e;
  }

  // The bending moment (N m per unit width) carried by the beam's column that x falls in, from its
  // particles' stresses: the moment of sigma_xx about the mid-thickness, with Hetenyi's sign
  // (negative where the top fibre is in tension). Each particle stands for a layer l0 thick (in 3D,
  // l0 thick and l0 wide, the sum divided by the width), and the sum is divided by 1 - 1 / n^2
  // (n rows), which makes it exact for a stress linear through the thickness, as beam theory's: the
  // midpoint sum of (y - y_mid)^2 over n layers is (h^3 / 12)(1 - 1 / n^2). `stresses` and
  // `reference` are per particle (ElasticSolver::stresses, reference_positions).
  template <int Dim>
  double column_moment(const MatArray<Dim, double>& stresses, const VecArray<Dim, double>& reference, double x,
                       double l0) const {
    check<Dim>(l0);
    if (stresses.size() != reference.size())
      detail::throw_invalid("scenes::FloatingIceBeam::column_moment", "needs one stress per particle");
    const auto column = static_cast<long>(std::floor(std::clamp(x, 0.0, beam_length_for(l0) - 0.5 * l0) / l0));
    const double mid = beam_bottom(l0) + 0.5 * thickness, rows = std::round(thickness / l0);
    double sum = 0;
    for (std::size_t i = 0; i < reference.size(); ++i)
      if (static_cast<long>(std::floor(reference[i][0] / l0)) == column)
        sum += stresses[i](0, 0) * (reference[i][1] - mid) * l0;
    if constexpr (Dim == 3) sum *= l0 / width_for(l0);
    return -sum / (1 - 1 / (rows * rows));
  }

  // Lengths rounded to whole spacings, the beam's bottom y_b on the water's lattice (a whole
  // number of spacings above the floor).
  double beam_length_for(double l0) const {
    const double L = beam_length > 0 ? beam_length : 5 / lambda();
    return std::ceil(L / l0 - 1e-9) * l0;
  }
  double beam_bottom(double l0) const { return std::round(water_depth / l0) * l0; }
  double width_for(double l0) const { return std::round(width / l0) * l0; }
  double tank_length(double l0) const { return beam_length_for(l0) + std::round(open_water / l0) * l0; }
  // The open water's surface: the beam's draft above y_b, to the nearest row.
  double open_water_level(double l0) const { return beam_bottom(l0) + std::round(draft() / l0) * l0; }
  // How far that level lies above the draft, m. Unless it is zero (a draft of whole rows,
  // rho_i h / rho_w = n l0), the beam starts out of equilibrium: its bottom carries rho_w g times
  // this more (less, when negative) than its weight, and the water's slow sloshing takes it up.
  double level_above_draft(double l0) const { return open_water_level(l0) - beam_bottom(l0) - draft(); }
  // How far an end load P raises the open water's level, and with it the beam away from the load:
  // the load displaces P / k of water per unit width, which spreads over the tank's whole surface,
  // under the beam and beside it (volume and vertical force balance), m. Hetenyi's semi-infinite
  // beam, measured from the undisturbed level, leaves it out: a column that started at rest is
  // deflection(P, x) - level_rise(P, l0) below its start.
  double level_rise(double P, double l0) const { return P / foundation_modulus() / tank_length(l0); }

  // The water and the tank (one wall layer, `dummy_layers` behind it) up to two spacings above
  // the beam's top, open above (y); in 3D the channel's side walls as well. The fluid's gravity
  // must point along -y (FluidParameters::gravity), in 3D too.
  template <int Dim = 2>
  ParticleSet<Dim> fluid_particles(double l0, int dummy_layers = 4) const {
    check<Dim>(l0);
    const double yb = beam_bottom(l0), L = beam_length_for(l0), T = tank_length(l0);
    ParticleSet<Dim> set;
    add_block(set, point<Dim>(0, 0, 0), point<Dim>(L, yb, width_for(l0)), l0, ParticleKind::fluid);
    add_block(set, point<Dim>(L, 0, 0), point<Dim>(T, open_water_level(l0), width_for(l0)), l0, ParticleKind::fluid);
    add_tank(set, point<Dim>(T, yb + thickness + 2 * l0, width_for(l0)), l0, dummy_layers, 1);
    return set;
  }

  // The beam, [0, L] x [y_b, y_b + h] (x [0, width] in 3D); `end_column` lists the particles of
  // the loaded end's column (x < l0).
  template <int Dim = 2>
  ParticleSet<Dim> beam_particles(double l0, std::vector<std::size_t>& end_column) const {
    check<Dim>(l0);
    const double yb = beam_bottom(l0);
    auto set = material_block<Dim>(point<Dim>(0, yb, 0), point<Dim>(beam_length_for(l0), yb + thickness, width_for(l0)),
                                   l0);
    end_column = select(set, [&](const Vec<Dim>& x) { return x[0] < l0; });
    return set;
  }

  // The particles of `end_column` (from beam_particles) in the row nearest the beam's
  // mid-thickness, the lower of two equally near: the roller's (see above), one particle in 2D,
  // one across the width in 3D. `beam` is the set beam_particles returned.
  template <int Dim>
  std::vector<std::size_t> roller_particles(const ParticleSet<Dim>& beam, const std::vector<std::size_t>& end_column,
                                            double l0) const {
    if (end_column.empty())
      detail::throw_invalid("scenes::FloatingIceBeam::roller_particles", "the end column is empty");
    const double mid = beam_bottom(l0) + 0.5 * thickness;
    double best_y = beam.positions().at(end_column.front())[1];
    for (const auto i : end_column) {
      const double y = beam.positions().at(i)[1];
      const double closer = std::abs(best_y - mid) - std::abs(y - mid);
      if (closer > 1e-9 * l0 || (std::abs(closer) <= 1e-9 * l0 && y < best_y)) best_y = y;
    }
    std::vector<std::size_t> row;
    for (const auto i : end_column)
      if (std::abs(beam.positions()[i][1] - best_y) <= 1e-9 * l0) row.push_back(i);
    return row;
  }
  // The 2D beam's roller: its one particle.
  std::size_t roller_particle(const ParticleSet<2>& beam, const std::vector<std::size_t>& end_column,
                              double l0) const {
    return roller_particles(beam, end_column, l0).front();
  }

  // The bottom row's particles beyond the end column (x >= l0), indices into `reference` (the
  // beam's reference positions): the face the water, or a Winkler foundation, loads as a
  // distributed traction, which the failure read-out treats as such
  // (ElasticSolver::mark_distributed_load). The end column carries the concentrated end load.
  template <int Dim>
  std::vector<std::size_t> wetted_bottom(const VecArray<Dim, double>& reference, double l0) const {
    check<Dim>(l0);
    const double row_top = beam_bottom(l0) + l0;
    std::vector<std::size_t> face;
    for (std::size_t i = 0; i < reference.size(); ++i)
      if (reference[i][1] < row_top && reference[i][0] >= l0) face.push_back(i);
    return face;
  }

 private:
  template <int Dim>
  static Vec<Dim> point(double x, double y, double z) {
    static_assert(Dim == 2 || Dim == 3, "scenes::FloatingIceBeam is 2D or 3D");
    if constexpr (Dim == 2) {
      return Vec<2>(x, y);
    } else {
      return Vec<3>(x, y, z);
    }
  }

  template <int Dim = 2>
  void check(double l0) const {
    if (!(l0 > 0) || !(thickness >= 2 * l0) || std::abs(thickness / l0 - std::round(thickness / l0)) > 1e-6)
      detail::throw_invalid("scenes::FloatingIceBeam",
                            "l0 must be positive and divide the thickness into at least two whole rows");
    if (!(water_depth >= 4 * l0) || !(open_water >= 4 * l0))
      detail::throw_invalid("scenes::FloatingIceBeam", "the water depth and the open water need at least 4 spacings");
    if (Dim == 3 && !(width >= 2 * l0))
      detail::throw_invalid("scenes::FloatingIceBeam", "in 3D the width needs at least 2 spacings");
  }
};

}  // namespace scenes
}  // namespace MPSFSI_ABI
}  // namespace mpsfsi
