// SPDX-License-Identifier: BSD-3-Clause
#pragma once

#include <cmath>
#include <cstdint>
#include <vector>

#include "mpsfsi/core/abi.hpp"
#include "mpsfsi/core/detail/format.hpp"
#include "mpsfsi/core/error.hpp"
#include "mpsfsi/core/particle_set.hpp"
#include "mpsfsi/scenes/lattice.hpp"

namespace mpsfsi {
inline namespace MPSFSI_ABI {
namespace scenes {

// Solid particles filling the block [lower, upper] with one particle per l0^d cell, at the cell
// centres (k + 1/2) l0: the material surface is the block surface, so a beam of height h has
// h/l0 rows. Every side must be a whole number of spacings (to 1e-6). Scalar is deduced from l0
// only, so Eigen expressions work as corners.
template <int Dim, class Scalar = double>
ParticleSet<Dim, Scalar> material_block(const typename ParticleSet<Dim, Scalar>::vec_type& lower,
                                        const typename ParticleSet<Dim, Scalar>::vec_type& upper, Scalar l0) {
  if (!(l0 > 0) || !std::isfinite(l0))
    detail::throw_invalid("scenes::material_block", "spacing l0 must be positive, got " + detail::format_number(l0));
  for (int k = 0; k < Dim; ++k) {
    const Scalar cells = (upper[k] - lower[k]) / l0;
    if (!(cells >= Scalar(1) - Scalar(1e-6)) || std::abs(cells - std::round(cells)) > Scalar(1e-6))
      detail::throw_invalid("scenes::material_block", "side " + std::to_string(k) + " (" +
                                                          detail::format_number(upper[k] - lower[k]) +
                                                          " m) is not a positive whole number of spacings l0 = " +
                                                          detail::format_number(l0));
  }
  const Vec<Dim, Scalar> half = Vec<Dim, Scalar>::Constant(l0 / 2);
  return lattice_box<Dim, Scalar>(lower + half, upper - half, l0, ParticleKind::solid);
}

// Indices of the particles for which pred(position) holds.
template <int Dim, class Scalar, class Predicate>
std::vector<std::size_t> select(const ParticleSet<Dim, Scalar>& set, Predicate pred) {
  std::vector<std::size_t> out;
  for (std::size_t i = 0; i < set.size(); ++i)
    if (pred(set.positions()[i])) out.push_back(i);
  return out;
}

// Appends the particles of `extra` to `set`; returns the index of the first appended particle.
template <int Dim, class Scalar>
std::size_t append(ParticleSet<Dim, Scalar>& set, const ParticleSet<Dim, Scalar>& extra) {
  const std::size_t first = set.size();
  for (std::size_t i = 0; i < extra.size(); ++i) set.add(extra.positions()[i], extra.kinds()[i], extra.velocities()[i]);
  return first;
}

}  // namespace scenes
}  // namespace MPSFSI_ABI
}  // namespace mpsfsi
