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

namespace mpsfsi {
inline namespace MPSFSI_ABI {

// Collision policies act on the predicted velocity u* of fluid particles:
//   template <int Dim> void apply(x, kinds, list, l0, u_star, scratch)
// FluidSolver passes the pairs within max(re_density, re_gradient) (2.1 l0 by default; always
// more than l0), every particle kind included.

// No collision model (a null object).
struct NoCollision {
  template <int Dim, class Scalar>
  void apply(const VecArray<Dim, Scalar>&, const std::vector<ParticleKind>&, const BasicNeighborList<Scalar>&,
             Scalar, VecArray<Dim, Scalar>&, VecArray<Dim, Scalar>&) const {}
};

// The collision model of Koshizuka's reference MPS implementation (Koshizuka, Shibata &
// Murotani, "Moving Particle Semi-implicit Method", 2018): a fluid particle i closer than
// distance_ratio * l0 to another particle j and approaching it exchanges momentum along the line
// of centres as an inelastic collision of equal masses with restitution coefficient e,
//   u_i -= (1 + e)/2 ((u_i - u_j) . n) n,  n = r_ij/|r_ij|, when (u_i - u_j) . n > 0;
// wall and dummy particles are not moved (they act as a fixed-velocity partner).
// Applied Jacobi-style (all pairs see the velocities before the collision), so the result does
// not depend on the thread count.
//
// distance_ratio = 0.9, the value of the widely circulated sample code of that book (some
// derived codes use 0.5 or 0.85). With 0.5, pairs between 0.5 and 0.9 l0 reach the PPE still
// approaching: a lone surface particle driven into a wall particle then makes that particle's
// pressure from eq 11's divergence term alone, and the gradient throws it back faster than it
// came (1.15 times its speed in the unit test; jets of up to 17 m/s off the end wall of the
// elastic-gate case at l0 = 2.5 mm). At 0.9 the same impact leaves it at 0.49 times, the gate
// case's fastest particle stays near Ritter's dam-break front speed 2.34 m/s (2.26 m/s at
// l0 = 2.5 mm, 2.84 m/s at 1 mm), and the fluid verification stays within its tolerances
// (hydrostatic 2D 0.58 % against 0.46 % at 0.5, dam-break front 3.2 % against 3.4 %;
// docs/validation/fluid.md).
struct KoshizukaCollision {
  double distance_ratio = 0.9;  // at most FluidSolver's re_density_ratio (the pairs it passes)
  double restitution = 0.2;

  template <int Dim, class Scalar>
  void apply(const VecArray<Dim, Scalar>& x, const std::vector<ParticleKind>& kinds,
             const BasicNeighborList<Scalar>& list, Scalar l0, VecArray<Dim, Scalar>& u,
             VecArray<Dim, Scalar>& scratch) const {
    const Scalar reach = static_cast<Scalar>(distance_ratio) * l0;
    const Scalar factor = Scalar(0.5) * (Scalar(1) + static_cast<Scalar>(restitution));
    scratch = u;
    MPSFSI_OMP(parallel for schedule(static))
    for (std::int64_t ii = 0; ii < static_cast<std::int64_t>(x.size()); ++ii) {
      const auto i = static_cast<std::size_t>(ii);
      if (kinds[i] != ParticleKind::fluid) continue;
      Vec<Dim, Scalar> change = Vec<Dim, Scalar>::Zero();
      for (Offset k = list.begin(i); k < list.end(i); ++k) {
        const auto j = static_cast<std::size_t>(list.indices[k]);
        const Vec<Dim, Scalar> r = x[j] - x[i];
        const Scalar d = detail::pair_distance(list, k, r);
        if (!(d < reach) || !(d > 0)) continue;
        const Vec<Dim, Scalar> n = r / d;
        const Scalar approach = (scratch[i] - scratch[j]).dot(n);
        if (approach > 0) change -= factor * approach * n;
      }
      u[i] += change;
    }
  }
};

}  // namespace MPSFSI_ABI
}  // namespace mpsfsi
