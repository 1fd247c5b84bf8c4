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

// Bond viscosity (docs/theory.md, section 3.6): a damping force along each intact bond against the
// rate at which it stretches,
//   f_i += coefficient sum_j beta_ij |r0_ij| ((v_j - v_i) . e_ij) e_ij,   e_ij = r_ij / |r_ij|,
// with beta_ij |r0_ij| = w0_ij / |r0_ij|. ElasticSolver passes
// coefficient = bond_viscosity rho c_p V d / n0. Cut bonds (beta = 0) and coincident particles
// add nothing. Each bond's w0 / |r0| is kept from the bonds as built (a bond's reference vector
// never changes) and set to zero when the bond is cut (bonds_changed), and
// ((v_j - v_i) . r) r / |r|^2 needs no square root: per bond, the loop reads two positions, two
// velocities, an index and one number.
template <int Dim>
class BondViscosity {
 public:
  // From the bonds as they are (also after a checkpoint is read).
  void initialize(const BondList<Dim, double>& bonds) {
    const auto& r0 = bonds.reference_vectors();
    const auto& beta = bonds.betas();
    weight_over_length_.resize(r0.size());
    for (std::size_t k = 0; k < r0.size(); ++k) weight_over_length_[k] = beta[k] * r0[k].norm();
  }

  // After cuts: the bonds of `particles` (both ends of every cut bond) with beta = 0 weigh nothing.
  void bonds_changed(const BondList<Dim, double>& bonds, const std::vector<std::size_t>& particles) {
    if (weight_over_length_.size() != bonds.num_bonds()) return;  // not initialised: no viscosity
    for (const std::size_t i : particles)
      for (Offset b = bonds.begin(i); b < bonds.end(i); ++b)
        if (bonds.beta(b) == 0) weight_over_length_[static_cast<std::size_t>(b)] = 0;
  }

  void add(const BondList<Dim, double>& bonds, const VecArray<Dim, double>& x, const VecArray<Dim, double>& v,
           double coefficient, VecArray<Dim, double>& force) const {
    const Offset* const offsets = bonds.offsets().data();
    const Index* const nb = bonds.neighbors().data();
    const double* const weight = weight_over_length_.data();
    MPSFSI_OMP(parallel for schedule(static))
    for (std::int64_t ii = 0; ii < static_cast<std::int64_t>(x.size()); ++ii) {
      const auto i = static_cast<std::size_t>(ii);
      Vec<Dim, double> sum = Vec<Dim, double>::Zero();
      for (Offset b = offsets[i]; b < offsets[i + 1]; ++b) {
        const auto k = static_cast<std::size_t>(b);
        const auto j = static_cast<std::size_t>(nb[k]);
        const Vec<Dim, double> r = x[j] - x[i];
        const double length2 = r.squaredNorm();
        if (weight[k] == 0 || length2 == 0) continue;  // cut, or coincident
        sum += (weight[k] * (v[j] - v[i]).dot(r) / length2) * r;
      }
      force[i] += coefficient * sum;
    }
  }

 private:
  std::vector<double> weight_over_length_;  // w0_ij / |r0_ij| = beta_ij |r0_ij| per directed bond
};

}  // namespace MPSFSI_ABI
}  // namespace mpsfsi
