// SPDX-License-Identifier: BSD-3-Clause
#pragma once

#include <cstdint>
#include <vector>

#include "mpsfsi/core/neighbor_list.hpp"
#include "mpsfsi/core/parallel.hpp"
#include "mpsfsi/core/particle_set.hpp"
#include "mpsfsi/core/types.hpp"
#include "mpsfsi/kernels/detail/pair.hpp"

namespace mpsfsi {

// Free-surface detectors. Each has
//   static void detect(x, kinds, list, n, n0, beta, l0, re, surface)
// filling surface[i] = 1 for fluid or wall particles that get the Dirichlet condition P = 0.
// Dummy particles are never in the PPE, so they are never flagged.

// The classic test of Koshizuka & Oka: n_i < beta n0.
struct NumberDensitySurface {
  template <int Dim, class Scalar>
  static void detect(const VecArray<Dim, Scalar>&, const std::vector<ParticleKind>& kinds,
                     const BasicNeighborList<Scalar>&, const std::vector<Scalar>& n, Scalar n0, Scalar beta,
                     Scalar, Scalar, std::vector<std::uint8_t>& surface) {
    surface.resize(n.size());
    MPSFSI_OMP(parallel for schedule(static))
    for (std::int64_t i = 0; i < static_cast<std::int64_t>(n.size()); ++i)
      surface[i] = (kinds[i] != ParticleKind::dummy && n[i] < beta * n0) ? 1 : 0;
  }
};

// Neighbour asymmetry (after Khayyer et al. 2009): a particle is at the surface when the mean
// position of its neighbours within re is displaced from it by more than `threshold` l0, or
// when n < 0.8 n0 (no interior particle loses a fifth of its neighbourhood). Unlike n < beta n0
// it does not flag interior particles whose density a disordered arrangement lowers by a few
// per cent (see examples/neighbor_demo), which would otherwise get P = 0 inside the fluid.
struct AsymmetrySurface {
  static constexpr double threshold = 0.2;
  static constexpr double always_surface_ratio = 0.8;

  template <int Dim, class Scalar>
  static void detect(const VecArray<Dim, Scalar>& x, const std::vector<ParticleKind>& kinds,
                     const BasicNeighborList<Scalar>& list, const std::vector<Scalar>& n, Scalar n0, Scalar /*beta*/,
                     Scalar l0, Scalar re, std::vector<std::uint8_t>& surface) {
    surface.resize(n.size());
    MPSFSI_OMP(parallel for schedule(static))
    for (std::int64_t ii = 0; ii < static_cast<std::int64_t>(n.size()); ++ii) {
      const auto i = static_cast<std::size_t>(ii);
      if (kinds[i] == ParticleKind::dummy) {
        surface[i] = 0;
        continue;
      }
      if (n[i] < Scalar(always_surface_ratio) * n0) {
        surface[i] = 1;
        continue;
      }
      Vec<Dim, Scalar> m = Vec<Dim, Scalar>::Zero();
      Scalar wsum = 0;
      for (Offset k = list.begin(i); k < list.end(i); ++k) {
        const Vec<Dim, Scalar> r = x[static_cast<std::size_t>(list.indices[k])] - x[i];
        const Scalar d = detail::pair_distance(list, k, r);
        if (d >= re) continue;
        m += r;
        wsum += 1;
      }
      const bool one_sided = wsum > 0 && (m / wsum).norm() > Scalar(threshold) * l0;
      surface[i] = one_sided ? 1 : 0;
    }
  }
};

}  // namespace mpsfsi
