// SPDX-License-Identifier: BSD-3-Clause
#pragma once

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

#include "mpsfsi/core/abi.hpp"
#include "mpsfsi/core/neighbor_list.hpp"
#include "mpsfsi/core/parallel.hpp"
#include "mpsfsi/core/particle_set.hpp"
#include "mpsfsi/core/types.hpp"
#include "mpsfsi/fsi/coupling_parameters.hpp"

namespace mpsfsi {
inline namespace MPSFSI_ABI {

// The fluid's load on a structure, eqs 18-19 (docs/theory.md, section 4.3). For each surface particle
// i of the structure, with outward normal n_i:
//   x_IF,i = x_i + 0.5 l0 n_i                                       (eq 19, Antoci et al. 2007)
//   P_IF,i = sum_j P_j w(|x_j - x_IF,i|) / sum_j w(|x_j - x_IF,i|)   (eq 18, fluid particles j)
//   f_i    = -P_IF,i l0^(d-1) n_i   (N; per unit thickness in 2D)
// Eq 18 as printed equates a force with an averaged pressure; the pressure acts on the particle's
// surface element l0^(d-1) against its outward normal. A surface particle with no fluid within re
// of its interface point carries no load; so do interior particles.
//
// Partial wetting: eq 18 normalises by the weights actually present, so a structure particle
// that sees a single fluid particle at the edge of its range (under a tank wall next to the water,
// at the rim of a droplet) would carry the full pressure on its whole element. With
// `full_weight` > 0 the denominator is max(sum_j w, full_weight), full_weight being the sum for a
// fully wetted flat interface (full_wetting_weight): eq 18 unchanged where the fluid covers the
// element, the load scaled by the wetted fraction where it does not. Measured on the hydrostatic
// plate (l0 = 0.0125 m): total load 1.04 W with eq 18 as printed (two particles per clamp under
// the side walls loaded), 1.00 W with the correction.
//
// Linear fit (InterfacePressure::linear_fit). The mean of eq 18 is the pressure about the
// weighted centroid of the fluid particles, which lies below x_IF, in the water: on hydrostatic
// water it reads about 0.6 of a spacing of depth too much. With the partial-wetting correction the
// mean is scaled by sum_j w / full_weight, and that sum depends on where the water's first row
// sits along the face: with Koshizuka's weight a row offset by half a spacing weighs 8 % less
// than one aligned with the structure's. The two errors move the load with the water's particle
// arrangement, by tens of pascals under a floating beam. The fit instead takes
//   min over (a, b) of sum_j w_j (P_j - a - b . (x_j - x_IF))^2,   P_IF = a,
// exact for any pressure linear in space, and scales it by min(1, sum_j w / full_weight) with
// full_weight the smallest weight sum of a fully wetted flat interface over the water's offsets
// along the face (least_full_wetting_weight), so that a wetted element carries its whole load
// however the water's rows sit. Where the fit is not determined (fewer than Dim + 1 particles, or
// all of them nearly on a line or plane: the moment matrix's smallest eigenvalue under
// kLinearFitConditionLimit times its largest), the mean of eq 18 is taken.
inline constexpr double kLinearFitConditionLimit = 1e-3;

// `candidates` lists, per structure particle, indices into the fluid solver's particle set within
// re + 0.5 l0 of x_i (a superset of those within re of x_IF,i); only ParticleKind::fluid entries
// count. Also returns P_IF per structure particle (zero where there is none).
template <class Weight, int Dim, class Scalar>
void interface_loads(const VecArray<Dim, Scalar>& structure_x, const VecArray<Dim, Scalar>& normal,
                     const std::vector<std::uint8_t>& on_surface, const ParticleSet<Dim, Scalar>& fluid,
                     const std::vector<Scalar>& fluid_pressure, const BasicNeighborList<Scalar>& candidates,
                     Scalar l0, Scalar re, Scalar full_weight, VecArray<Dim, Scalar>& force,
                     std::vector<Scalar>& interface_pressure,
                     InterfacePressure form = InterfacePressure::weighted_mean) {
  using Moment = Eigen::Matrix<Scalar, Dim + 1, Dim + 1>;
  using Basis = Eigen::Matrix<Scalar, Dim + 1, 1>;
  const std::size_t n = structure_x.size();
  const auto& xf = fluid.positions();
  const auto& kind = fluid.kinds();
  const Scalar area = std::pow(l0, Scalar(Dim - 1));
  force.resize(n);
  interface_pressure.resize(n);
  MPSFSI_OMP(parallel for schedule(static))
  for (std::int64_t ii = 0; ii < static_cast<std::int64_t>(n); ++ii) {
    const auto i = static_cast<std::size_t>(ii);
    Scalar pressure = 0;
    if (on_surface[i]) {
      const Vec<Dim, Scalar> x_if = structure_x[i] + Scalar(0.5) * l0 * normal[i];
      Scalar weighted = 0, weights = 0;
      Moment moment = Moment::Zero();
      Basis moment_pressure = Basis::Zero();
      int in_range = 0;
      for (Offset k = candidates.begin(i); k < candidates.end(i); ++k) {
        const auto j = static_cast<std::size_t>(candidates.indices[static_cast<std::size_t>(k)]);
        if (kind[j] != ParticleKind::fluid) continue;
        const Vec<Dim, Scalar> r = xf[j] - x_if;
        const Scalar w = Weight::value(r.norm(), re);
        if (form == InterfacePressure::weighted_mean) {
          weighted += w * fluid_pressure[j];
          weights += w;
        } else if (w > 0) {
          Basis basis;
          basis << Scalar(1), r / l0;  // in spacings, so that the moments are of one order
          moment.noalias() += w * basis * basis.transpose();
          moment_pressure += (w * fluid_pressure[j]) * basis;
          ++in_range;
        }
      }
      if (form == InterfacePressure::linear_fit) {
        // The moments' constant entries are the mean's sums.
        weights = moment(0, 0);
        weighted = moment_pressure[0];
      }
      if (weights > 0 && form == InterfacePressure::weighted_mean) {
        pressure = weighted / std::max(weights, full_weight);
      } else if (weights > 0) {
        Scalar value = weighted / weights;
        if (in_range > Dim) {
          const Eigen::SelfAdjointEigenSolver<Moment> eigen(moment);
          const Basis lambda = eigen.eigenvalues();
          if (lambda.minCoeff() > Scalar(kLinearFitConditionLimit) * lambda.maxCoeff())
            value = eigen.eigenvectors().row(0).dot(
                lambda.cwiseInverse().asDiagonal() * (eigen.eigenvectors().transpose() * moment_pressure));
        }
        pressure = value * (weights / std::max(weights, full_weight));
      }
    }
    interface_pressure[i] = pressure;
    force[i] = (-pressure * area) * normal[i];
  }
}

namespace detail {

// The weight sum about an interface point of fluid particles on the lattice (k + 1/2) l0 on one
// side of it, shifted by (s, t) l0 along the face.
template <class Weight, int Dim, class Scalar>
Scalar lattice_wetting_weight(Scalar l0, Scalar re, Scalar s, Scalar t) {
  const int reach = static_cast<int>(std::ceil(re / l0)) + 2;
  Scalar sum = 0;
  const int lo2 = Dim == 3 ? -reach : 0, hi2 = Dim == 3 ? reach : 0;
  for (int a = -reach; a <= reach; ++a)
    for (int c = lo2; c <= hi2; ++c)
      for (int k = 0; k <= reach; ++k) {
        Vec<Dim, Scalar> r;
        r[0] = (a + s) * l0;
        if constexpr (Dim == 3) r[1] = (c + t) * l0;
        r[Dim - 1] = (k + Scalar(0.5)) * l0;
        sum += Weight::value(r.norm(), re);
      }
  return sum;
}

}  // namespace detail

// The weight sum of eq 18 at a fully wetted flat interface: fluid particles on the lattice
// (k + 1/2) l0 on one side of the interface point, aligned with it along the face.
template <class Weight, int Dim, class Scalar>
Scalar full_wetting_weight(Scalar l0, Scalar re) {
  return detail::lattice_wetting_weight<Weight, Dim, Scalar>(l0, re, 0, 0);
}

// The smallest weight sum of a fully wetted flat interface over the lattice's offsets along the
// face, (s, t) l0 with s and t in [0, 1/2] (the rest by symmetry), sampled at 1/20 of a spacing.
// With Koshizuka's weight at re = 2.1 l0 the smallest is at half a spacing: 0.918 of the aligned
// sum in 2D.
template <class Weight, int Dim, class Scalar>
Scalar least_full_wetting_weight(Scalar l0, Scalar re) {
  constexpr int samples = 10;
  Scalar least = std::numeric_limits<Scalar>::max();
  for (int si = 0; si <= samples; ++si)
    for (int ti = 0; ti <= (Dim == 3 ? samples : 0); ++ti)
      least = std::min(least, detail::lattice_wetting_weight<Weight, Dim, Scalar>(
                                  l0, re, Scalar(si) / (2 * samples), Scalar(ti) / (2 * samples)));
  return least;
}

}  // namespace MPSFSI_ABI
}  // namespace mpsfsi
