// SPDX-License-Identifier: BSD-3-Clause
#pragma once

#include <cstdint>
#include <vector>

#include "mpsfsi/core/abi.hpp"
#include "mpsfsi/core/parallel.hpp"
#include "mpsfsi/core/types.hpp"
#include "mpsfsi/solid/bonds.hpp"

namespace mpsfsi {
inline namespace MPSFSI_ABI {

// Outward normals of a structure from the gradient of its number density (docs/theory.md,
// section 4.1), over the intact bonds at the current positions:
//   g_i = sum_j w(|r0_ij|) (x_i - x_j) / |x_i - x_j|,   n_i = g_i / |g_i|.
// The reference weights make the sum see the bonds, not whatever lies near i now: a cut bond
// drops out, so the faces of a crack get normals pointing into it, and two bodies in contact do
// not hide each other's surfaces.
//
// A particle is on the surface when |g_i| >= threshold n0, n0 being the number density of a full
// neighbourhood. On a flat face (re = 2.1 l0) the outer layer has |g|/n0 = 0.28 in 2D and 0.21 in
// 3D, the layer beneath it below 0.01 in both, so the default threshold 0.1 picks exactly the outer
// layer. Interior particles get a zero normal.
//
// A particle that has lost bonds on opposite sides (a sliver between two cracks, a loose
// fragment of one particle) has a small g but is exposed all the same: it is on the surface too
// when its intact-bond number density sum_j w(|r0_ij|) falls below (1 - threshold) n0 (an
// interior particle has n0, the layer beneath a flat face 0.99 n0 in 2D), with a zero normal
// when |g| < threshold n0 (no direction to load it along).
template <int Dim, class Scalar>
void structure_normals(const BondList<Dim, Scalar>& bonds, const VecArray<Dim, Scalar>& x, Scalar n0,
                       Scalar threshold, VecArray<Dim, Scalar>& normal, std::vector<std::uint8_t>& on_surface) {
  const std::size_t n = x.size();
  normal.resize(n);
  on_surface.resize(n);
  MPSFSI_OMP(parallel for schedule(static))
  for (std::int64_t ii = 0; ii < static_cast<std::int64_t>(n); ++ii) {
    const auto i = static_cast<std::size_t>(ii);
    Vec<Dim, Scalar> g = Vec<Dim, Scalar>::Zero();
    Scalar intact_density = 0;
    for (Offset b = bonds.begin(i); b < bonds.end(i); ++b) {
      const Scalar w = bonds.weight(b);
      if (w == 0) continue;
      intact_density += w;
      const Vec<Dim, Scalar> r = x[i] - x[static_cast<std::size_t>(bonds.neighbor(b))];
      const Scalar len = r.norm();
      if (len > 0) g += (w / len) * r;
    }
    const Scalar magnitude = g.norm();
    const bool directed = magnitude >= threshold * n0 && magnitude > 0;
    on_surface[i] = directed || intact_density < (1 - threshold) * n0 ? 1 : 0;
    normal[i] = directed ? Vec<Dim, Scalar>(g / magnitude) : Vec<Dim, Scalar>::Zero();
  }
}

}  // namespace MPSFSI_ABI
}  // namespace mpsfsi
