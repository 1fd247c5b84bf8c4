// SPDX-License-Identifier: BSD-3-Clause
#pragma once

#include <cstdint>
#include <vector>

#include "mpsfsi/core/abi.hpp"
#include "mpsfsi/core/neighbor_list.hpp"
#include "mpsfsi/core/parallel.hpp"
#include "mpsfsi/core/particle_set.hpp"
#include "mpsfsi/core/types.hpp"

namespace mpsfsi {
inline namespace MPSFSI_ABI {

// The structure's coupling term in the fluid predictor, eqs 9-10: f_S->F,i = d u_IF / dt, the
// acceleration of the interface next to fluid particle i. It is taken as the w-weighted average
// of the accelerations a_s of the structure's surface particles within re of i:
//   f_i = sum_s w(|x_i - x_s|) a_s / sum_s w(|x_i - x_s|),
// zero for fluid particles with no structure surface within re.
//
// `candidates` lists, per structure particle s, indices into the fluid solver's particle set near
// it (as for interface_loads). The accumulation is a scatter from structure to fluid, done on one
// thread: it touches only the fluid next to the interface. `weight_sum` is scratch.
template <class Weight, int Dim, class Scalar>
void interface_accelerations(const VecArray<Dim, Scalar>& structure_x, const VecArray<Dim, Scalar>& structure_a,
                             const std::vector<std::uint8_t>& on_surface, const ParticleSet<Dim, Scalar>& fluid,
                             const BasicNeighborList<Scalar>& candidates, Scalar re,
                             VecArray<Dim, Scalar>& fluid_acceleration, std::vector<Scalar>& weight_sum) {
  const std::size_t nf = fluid.size();
  const auto& xf = fluid.positions();
  const auto& kind = fluid.kinds();
  fluid_acceleration.assign(nf, Vec<Dim, Scalar>::Zero());
  weight_sum.assign(nf, Scalar(0));
  for (std::size_t s = 0; s < structure_x.size(); ++s) {
    if (!on_surface[s]) continue;
    for (Offset k = candidates.begin(s); k < candidates.end(s); ++k) {
      const auto j = static_cast<std::size_t>(candidates.indices[static_cast<std::size_t>(k)]);
      if (kind[j] != ParticleKind::fluid) continue;
      const Scalar w = Weight::value((xf[j] - structure_x[s]).norm(), re);
      fluid_acceleration[j] += w * structure_a[s];
      weight_sum[j] += w;
    }
  }
  MPSFSI_OMP(parallel for schedule(static))
  for (std::int64_t jj = 0; jj < static_cast<std::int64_t>(nf); ++jj) {
    const auto j = static_cast<std::size_t>(jj);
    if (weight_sum[j] > 0) fluid_acceleration[j] /= weight_sum[j];
  }
}

}  // namespace MPSFSI_ABI
}  // namespace mpsfsi
