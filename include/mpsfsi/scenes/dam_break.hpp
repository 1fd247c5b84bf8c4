// SPDX-License-Identifier: BSD-3-Clause
#pragma once

#include <algorithm>
#include <cmath>

#include "mpsfsi/core/abi.hpp"
#include "mpsfsi/core/particle_set.hpp"
#include "mpsfsi/core/types.hpp"
#include "mpsfsi/scenes/tank.hpp"

namespace mpsfsi {
inline namespace MPSFSI_ABI {
namespace scenes {

// The dam break of Martin & Moyce (1952) and Koshizuka & Oka (1996): a water column `width` wide
// and `height` high against the left wall of an open tank `tank_length` long and `tank_height`
// high (3D: the column and the tank are `depth` deep). The left wall is at x = 0, the floor at
// y = 0 (z = 0 in 3D; the vertical is the last axis).
template <int Dim>
ParticleSet<Dim> dam_break(double width, double height, double tank_length, double tank_height, double l0,
                           double depth = 0) {
  ParticleSet<Dim> set;
  Vec<Dim> column = Vec<Dim>::Constant(depth);
  column[0] = width;
  column[Dim - 1] = height;
  Vec<Dim> tank = Vec<Dim>::Constant(depth);
  tank[0] = tank_length;
  tank[Dim - 1] = tank_height;
  add_block<Dim, double>(set, Vec<Dim>::Zero(), column, l0, ParticleKind::fluid);
  add_tank<Dim, double>(set, tank, l0);
  return set;
}

// Surge front: the largest x reached by fluid particles on the floor (within two spacings of
// it), plus half a spacing for the particle's own extent. Droplets thrown ahead of the front do
// not count unless they touch the floor.
template <int Dim>
double surge_front(const ParticleSet<Dim>& set, double l0) {
  double front = 0;
  for (std::size_t i = 0; i < set.size(); ++i)
    if (set.kinds()[i] == ParticleKind::fluid && set.positions()[i][Dim - 1] < 2 * l0)
      front = std::max(front, set.positions()[i][0] + 0.5 * l0);
  return front;
}

// Residual column height at the left wall: the highest fluid particle within two spacings of
// it, plus half a spacing.
template <int Dim>
double column_height(const ParticleSet<Dim>& set, double l0) {
  double top = 0;
  for (std::size_t i = 0; i < set.size(); ++i)
    if (set.kinds()[i] == ParticleKind::fluid && set.positions()[i][0] < 2 * l0)
      top = std::max(top, set.positions()[i][Dim - 1] + 0.5 * l0);
  return top;
}

}  // namespace scenes
}  // namespace MPSFSI_ABI
}  // namespace mpsfsi
