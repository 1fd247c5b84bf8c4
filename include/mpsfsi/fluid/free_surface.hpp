// SPDX-License-Identifier: BSD-3-Clause
#pragma once

#include <cstdint>
#include <vector>

#include "mpsfsi/core/abi.hpp"
#include "mpsfsi/core/neighbor_list.hpp"
#include "mpsfsi/core/parallel.hpp"
#include "mpsfsi/core/particle_set.hpp"
#include "mpsfsi/core/types.hpp"
#include "mpsfsi/kernels/detail/pair.hpp"
#include "mpsfsi/kernels/lattice_constants.hpp"
#include "mpsfsi/kernels/weight.hpp"

namespace mpsfsi {
inline namespace MPSFSI_ABI {

// Free-surface detectors. Each has
//   static void detect(x, kinds, list, n, n0, beta, l0, re, surface)
// filling surface[i] = 1 for fluid or wall particles that get the Dirichlet condition P = 0.
// Dummy particles are never in the PPE, so they are never flagged.

namespace detail {
// The two-stage tests: a fluid or wall particle with n_i < beta n0 is at the surface when
// second_test(i) also holds; the second test runs only for those that fail the first.
template <class Scalar, class SecondTest>
void two_stage_surface(const std::vector<ParticleKind>& kinds, const std::vector<Scalar>& n, Scalar n0, Scalar beta,
                       std::vector<std::uint8_t>& surface, const SecondTest& second_test) {
  surface.resize(n.size());
  MPSFSI_OMP(parallel for schedule(static))
  for (std::int64_t ii = 0; ii < static_cast<std::int64_t>(n.size()); ++ii) {
    const auto i = static_cast<std::size_t>(ii);
    surface[i] = kinds[i] != ParticleKind::dummy && n[i] < beta * n0 && second_test(i) ? 1 : 0;
  }
}
}  // namespace detail

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

// The test of Lee et al. 2011 (PNU-MPS): a particle is at the surface when n_i < beta n0 AND
// it has fewer than count_ratio N0 neighbours within re, N0 being the count of a full lattice
// neighbourhood. The count does not change when a disordered arrangement moves particles within
// re, unlike n with the singular weight, so interior particles keep their pressure.
// Measured: the 2D hydrostatic tank is as good as with NumberDensitySurface (worst particle
// 2.3 %), but in the 2D dam break (l0 = a/50, dt = 2e-4 s) a splash particle reaches 5 m/s by
// t = 0.19 s, which the default detector does not allow; so it is not the default.
struct NeighborCountSurface {
  static constexpr double count_ratio = 0.85;

  template <int Dim, class Scalar>
  static void detect(const VecArray<Dim, Scalar>& x, const std::vector<ParticleKind>& kinds,
                     const BasicNeighborList<Scalar>& list, const std::vector<Scalar>& n, Scalar n0, Scalar beta,
                     Scalar l0, Scalar re, std::vector<std::uint8_t>& surface) {
    const double full = static_cast<double>(ideal_neighbor_count<Dim>(l0, re));
    detail::two_stage_surface(kinds, n, n0, beta, surface, [&](std::size_t i) {
      int count = 0;
      for (Offset k = list.begin(i); k < list.end(i); ++k) {
        const Vec<Dim, Scalar> r = x[static_cast<std::size_t>(list.indices[k])] - x[i];
        count += detail::pair_distance(list, k, r) < re ? 1 : 0;
      }
      return count < count_ratio * full;
    });
  }
};

// The two-stage test of Tsukamoto, Cheng & Motezuki 2016 (neighbour particle centroid deviation,
// NPCD): a particle with n_i < beta n0 is at the surface only if the weighted centroid of its
// neighbours within re lies more than deviation_ratio l0 away from it,
//   |sum_j w_ij r_ij| / sum_j w_ij > 0.2 l0,
// with every neighbour counted, walls and dummies included. A particle whose neighbourhood is
// closed on all sides (water under a structure, in a corner between a structure and a wall) has
// its neighbours' centroid near itself even when disorder lowers its n, so it keeps its pressure;
// at a free surface the missing half of the neighbourhood moves the centroid inwards, by 0.49 l0
// for the top row of a 2D lattice (re = 2.1 l0) and more at corners. 0.2 l0 is the threshold of
// Tsukamoto et al. Weight is the weight function the deviation is taken with (the solver's, for
// consistency).
// One of the three settings for water under a structure (docs/theory.md, section 2.9): with
// WallCondition::neumann and the full density term, water under a fixed lid stays on it
// (docs/validation/fluid.md). Not the default: the defaults' figures are validated as they are.
template <class Weight = KoshizukaWeight>
struct CentroidDeviationSurface {
  static constexpr double deviation_ratio = 0.2;

  template <int Dim, class Scalar>
  static void detect(const VecArray<Dim, Scalar>& x, const std::vector<ParticleKind>& kinds,
                     const BasicNeighborList<Scalar>& list, const std::vector<Scalar>& n, Scalar n0, Scalar beta,
                     Scalar l0, Scalar re, std::vector<std::uint8_t>& surface) {
    const Scalar limit = static_cast<Scalar>(deviation_ratio) * l0;
    detail::two_stage_surface(kinds, n, n0, beta, surface, [&](std::size_t i) {
      Vec<Dim, Scalar> weighted = Vec<Dim, Scalar>::Zero();
      Scalar weight_sum = 0;
      for (Offset k = list.begin(i); k < list.end(i); ++k) {
        const Vec<Dim, Scalar> r = x[static_cast<std::size_t>(list.indices[k])] - x[i];
        const Scalar w = Weight::value(detail::pair_distance(list, k, r), re);
        weighted += w * r;
        weight_sum += w;
      }
      // No neighbour within re: an isolated particle, at the surface.
      return !(weight_sum > 0) || weighted.norm() > limit * weight_sum;
    });
  }
};

}  // namespace MPSFSI_ABI
}  // namespace mpsfsi
