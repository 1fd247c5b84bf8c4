// SPDX-License-Identifier: BSD-3-Clause
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>

#include "mpsfsi/core/abi.hpp"
#include "mpsfsi/core/error.hpp"
#include "mpsfsi/core/particle_set.hpp"
#include "mpsfsi/core/types.hpp"
#include "mpsfsi/scenes/lattice.hpp"
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

// Part `part` of `parts` of the same scene, for a distributed run in which no process builds the
// whole set: the column's rows along the vertical are dealt out in contiguous bands, one per
// part, and part 0 also holds the tank (a few layers around the water: O(N^((Dim-1)/Dim))
// particles). Together the parts are dam_break(...), the positions equal to round-off.
template <int Dim>
ParticleSet<Dim> dam_break_part(double width, double height, double tank_length, double tank_height, double l0,
                                double depth, int part, int parts) {
  if (parts < 1 || part < 0 || part >= parts)
    detail::throw_invalid("scenes::dam_break_part", "part " + std::to_string(part) + " of " + std::to_string(parts) +
                                                        ": need 0 <= part < parts");
  if (!(l0 > 0) || !(height > 0)) detail::throw_invalid("scenes::dam_break_part", "l0 and height must be positive");
  ParticleSet<Dim> set;
  const std::int64_t rows = lattice_count<double>(0, height, l0) - 1;
  const std::int64_t first = rows * part / parts, last = rows * (part + 1) / parts;
  Vec<Dim> lower = Vec<Dim>::Zero(), upper = Vec<Dim>::Constant(depth);
  upper[0] = width;
  lower[Dim - 1] = static_cast<double>(first) * l0;
  upper[Dim - 1] = static_cast<double>(last) * l0;
  if (last > first) add_block<Dim, double>(set, lower, upper, l0, ParticleKind::fluid);
  if (part == 0) {
    Vec<Dim> tank = Vec<Dim>::Constant(depth);
    tank[0] = tank_length;
    tank[Dim - 1] = tank_height;
    add_tank<Dim, double>(set, tank, l0);
  }
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
