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

namespace mpsfsi {
inline namespace MPSFSI_ABI {
namespace scenes {

// Convention of the scenes: a region [0, L] is filled by particles at (k + 1/2) l0, so each
// particle stands for the cell of side l0 around it and the region's faces lie half a spacing
// outside its outermost particles.

// Appends the particles of kind `kind` that fill the region [lower, upper] (its faces, not its
// outer particles) to `set`.
template <int Dim, class Scalar>
void add_block(ParticleSet<Dim, Scalar>& set, const typename ParticleSet<Dim, Scalar>::vec_type& lower,
               const typename ParticleSet<Dim, Scalar>::vec_type& upper, Scalar l0, ParticleKind kind) {
  const Vec<Dim, Scalar> half = Vec<Dim, Scalar>::Constant(l0 / 2);
  const auto block = lattice_box<Dim, Scalar>(lower + half, upper - half, l0, kind);
  const std::size_t start = set.size();
  set.resize(start + block.size());
  for (std::size_t k = 0; k < block.size(); ++k) {
    set.positions()[start + k] = block.positions()[k];
    set.kinds()[start + k] = kind;
  }
}

// Appends an open-top tank around the region [0, size]: one layer of wall particles against
// the region (in the PPE) and `dummy_layers` layers of dummy particles behind it (number
// density only), on the bottom and the sides, up to the region's top. `up` is the vertical axis,
// open at the top: the last one by default (y in 2D, z in 3D).
template <int Dim, class Scalar>
void add_tank(ParticleSet<Dim, Scalar>& set, const typename ParticleSet<Dim, Scalar>::vec_type& size, Scalar l0,
              int dummy_layers = 2, int up = Dim - 1) {
  if (!(l0 > 0) || !size.allFinite() || (size.array() <= 0).any() || dummy_layers < 0)
    detail::throw_invalid("scenes::add_tank", "size and l0 must be positive, dummy_layers >= 0");
  if (up < 0 || up >= Dim) detail::throw_invalid("scenes::add_tank", "the vertical axis must be one of the set's axes");
  const int layers = 1 + dummy_layers;
  std::int64_t lo[3] = {0, 0, 0}, hi[3] = {0, 0, 0}, cells[3] = {1, 1, 1};
  for (int k = 0; k < Dim; ++k) {
    cells[k] = lattice_count<Scalar>(0, size[k], l0) - 1;  // particles across the region
    lo[k] = -layers;
    hi[k] = cells[k] + layers - 1;
  }
  hi[up] = cells[up] - 1;  // open top
  for (std::int64_t c = lo[2]; c <= hi[2]; ++c)
    for (std::int64_t b = lo[1]; b <= hi[1]; ++b)
      for (std::int64_t a = lo[0]; a <= hi[0]; ++a) {
        const std::int64_t idx[3] = {a, b, c};
        std::int64_t depth = -1;  // layers outside the region, -1 inside
        for (int k = 0; k < Dim; ++k) {
          if (idx[k] < 0) depth = std::max(depth, -idx[k] - 1);
          if (idx[k] >= cells[k]) depth = std::max(depth, idx[k] - cells[k]);
        }
        if (depth < 0) continue;
        Vec<Dim, Scalar> p;
        for (int k = 0; k < Dim; ++k) p[k] = (static_cast<Scalar>(idx[k]) + Scalar(0.5)) * l0;
        set.add(p, depth == 0 ? ParticleKind::wall : ParticleKind::dummy);
      }
}

}  // namespace scenes
}  // namespace MPSFSI_ABI
}  // namespace mpsfsi
