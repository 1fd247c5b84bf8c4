// SPDX-License-Identifier: BSD-3-Clause
#pragma once

#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "mpsfsi/core/abi.hpp"
#include "mpsfsi/core/error.hpp"
#include "mpsfsi/core/particle_set.hpp"
#include "mpsfsi/scenes/solid_block.hpp"
#include "mpsfsi/scenes/tank.hpp"

namespace mpsfsi {
inline namespace MPSFSI_ABI {
namespace scenes {

// Dam break through an elastic gate (Antoci, Gallati & Sibilla 2007): water `water_width` wide
// and `water_height` high, held on its right by a rubber gate `gate_length` long and
// `gate_thickness` thick, clamped at its top end; above the gate a rigid wall holds the rest of
// the column. The gate's lower end is free and rests on the floor; at t = 0 the water pushes it
// open. The floor runs `floor_length` downstream to a low end wall. In 3D everything is extruded
// by `width` between two side walls (along z), so y is the vertical in 2D and in 3D: pass
// gravity_vector() to both solvers (FluidParameters' default gravity points along the last axis,
// which is z in 3D). Lengths are rounded to whole numbers of spacings l0; the rounded geometry is
// what the scene builds (gate_length_used()).
struct ElasticGate {
  double water_width = 0.1, water_height = 0.14;
  double gate_length = 0.079, gate_thickness = 0.005;
  double density = 1100, youngs_modulus = 10e6, poisson_ratio = 0.4;  // rubber
  double floor_length = 0.3, end_wall_height = 0.03, width = 0.02;     // width only in 3D
  int wall_layers = 3;  // one wall layer and the rest dummy; also the clamp's length in l0
  double gravity = 9.81;

  // Gravity along -y, the scene's vertical in 2D and 3D.
  template <int Dim>
  Vec<Dim> gravity_vector() const {
    Vec<Dim> g = Vec<Dim>::Zero();
    g[1] = -gravity;
    return g;
  }

  template <class Parameters>
  void set_material(Parameters& p) const {
    p.density = density;
    p.youngs_modulus = youngs_modulus;
    p.poisson_ratio = poisson_ratio;
  }

  static long cells(double length, double l0) { return std::max(1L, std::lround(length / l0)); }
  double gate_length_used(double l0) const { return cells(gate_length, l0) * l0; }

  // Water, floor, left wall, the rigid wall above the gate and the end wall (and the side walls
  // in 3D), each with one wall layer on its wetted face and dummies behind.
  template <int Dim>
  ParticleSet<Dim> fluid_particles(double l0) const {
    check(l0);
    const double d = wall_layers * l0;
    const double w = cells(water_width, l0) * l0, h = cells(water_height, l0) * l0;
    const double t = cells(gate_thickness, l0) * l0, top = gate_length_used(l0) + d;
    const double wall_top = h + 4 * l0, x_end = w + cells(floor_length, l0) * l0;
    const double z = Dim == 3 ? cells(width, l0) * l0 : 0;
    ParticleSet<Dim> set = box<Dim>(0, w, 0, h, z, l0, ParticleKind::fluid, -1, 0);
    append(set, box<Dim>(-d, 0, 0, wall_top, z, l0, ParticleKind::dummy, 0, +1));            // left wall
    append(set, box<Dim>(-d, x_end + d, -d, 0, z, l0, ParticleKind::dummy, 1, +1));          // floor
    append(set, box<Dim>(w, w + t, top, wall_top, z, l0, ParticleKind::dummy, 0, -1));       // above the gate
    append(set, box<Dim>(x_end, x_end + d, 0, cells(end_wall_height, l0) * l0, z, l0, ParticleKind::dummy, 0, -1));
    if constexpr (Dim == 3) {
      for (const int side : {-1, +1}) {
        auto wall = box<3>(-d, x_end + d, -d, wall_top, d, l0, ParticleKind::dummy, 2, side > 0 ? -1 : +1);
        const double shift = side < 0 ? -d : z;
        for (auto& p : wall.positions()) p[2] += shift;
        append(set, wall);
      }
    }
    return set;
  }

  // The gate, x in [water_width, + thickness], y in [0, gate length + clamp], the clamped
  // particles (above the gate length, inside the rigid wall) in `clamped`, `tip` the particle at
  // the centre of the free end.
  template <int Dim>
  ParticleSet<Dim> gate_particles(double l0, std::vector<std::size_t>& clamped, std::size_t& tip) const {
    check(l0);
    const double w = cells(water_width, l0) * l0, t = cells(gate_thickness, l0) * l0;
    const double len = gate_length_used(l0), z = Dim == 3 ? cells(width, l0) * l0 : 0;
    Vec<Dim> lower = Vec<Dim>::Zero(), upper = Vec<Dim>::Zero();
    lower[0] = w;
    upper[0] = w + t;
    upper[1] = len + wall_layers * l0;
    if constexpr (Dim == 3) upper[2] = z;
    auto set = material_block<Dim>(lower, upper, l0);
    clamped = select(set, [&](const Vec<Dim>& x) { return x[1] > len; });
    tip = 0;
    double best = 1e300;
    for (std::size_t i = 0; i < set.size(); ++i) {
      const Vec<Dim>& x = set.positions()[i];
      double dist = std::abs(x[0] - (w + t / 2)) + x[1];
      if constexpr (Dim == 3) dist += std::abs(x[2] - z / 2);
      if (dist < best) best = dist, tip = i;
    }
    return set;
  }

 private:
  void check(double l0) const {
    if (!(l0 > 0) || gate_thickness < 2 * l0 - 1e-12)
      detail::throw_invalid("scenes::ElasticGate", "l0 must be positive and at most half the gate thickness");
  }

  // The box [x0, x1] x [y0, y1] (x [0, z] in 3D) of kind `kind`; if wet_axis >= 0, its outermost
  // layer on the side `wet_side` of that axis becomes ParticleKind::wall.
  template <int Dim>
  static ParticleSet<Dim> box(double x0, double x1, double y0, double y1, double z, double l0, ParticleKind kind,
                              int wet_axis, int wet_side) {
    Vec<Dim> lower = Vec<Dim>::Zero(), upper = Vec<Dim>::Zero();
    lower[0] = x0;
    upper[0] = x1;
    lower[1] = y0;
    upper[1] = y1;
    if constexpr (Dim == 3) upper[2] = z;
    ParticleSet<Dim> set;
    add_block(set, lower, upper, l0, kind);
    if (wet_axis < 0) return set;
    for (std::size_t i = 0; i < set.size(); ++i) {
      const double c = set.positions()[i][wet_axis];
      const double face = wet_side > 0 ? upper[wet_axis] - l0 / 2 : lower[wet_axis] + l0 / 2;
      if (std::abs(c - face) < l0 / 4) set.kinds()[i] = ParticleKind::wall;
    }
    return set;
  }
};

}  // namespace scenes
}  // namespace MPSFSI_ABI
}  // namespace mpsfsi
