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

}  // namespace mpsfsi
