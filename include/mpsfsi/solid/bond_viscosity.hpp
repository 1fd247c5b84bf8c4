// SPDX-License-Identifier: BSD-3-Clause
#pragma once

#include <cstdint>

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
// add nothing.
template <int Dim>
void add_bond_viscosity(const BondList<Dim, double>& bonds, const VecArray<Dim, double>& x,
                        const VecArray<Dim, double>& v, double coefficient, VecArray<Dim, double>& force) {
  const auto& offsets = bonds.offsets();
  const auto& nb = bonds.neighbors();
  const auto& r0 = bonds.reference_vectors();
  const auto& beta = bonds.betas();
  MPSFSI_OMP(parallel for schedule(static))
  for (std::int64_t ii = 0; ii < static_cast<std::int64_t>(x.size()); ++ii) {
    const auto i = static_cast<std::size_t>(ii);
    Vec<Dim, double> sum = Vec<Dim, double>::Zero();
    for (Offset b = offsets[i]; b < offsets[i + 1]; ++b) {
      const auto k = static_cast<std::size_t>(b);
      const auto j = static_cast<std::size_t>(nb[k]);
      const Vec<Dim, double> r = x[j] - x[i];
      const double len = r.norm();
      if (beta[k] == 0 || len == 0) continue;
      const Vec<Dim, double> e = r / len;
      sum += (beta[k] * r0[k].norm() * (v[j] - v[i]).dot(e)) * e;  // w0 / |r0| = beta |r0|
    }
    force[i] += coefficient * sum;
  }
}

}  // namespace MPSFSI_ABI
}  // namespace mpsfsi
