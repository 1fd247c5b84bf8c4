// SPDX-License-Identifier: BSD-3-Clause
#pragma once

#include <Eigen/Eigenvalues>
#include <cstdint>
#include <vector>

#include "mpsfsi/core/abi.hpp"
#include "mpsfsi/core/neighbor_list.hpp"
#include "mpsfsi/core/parallel.hpp"
#include "mpsfsi/core/types.hpp"
#include "mpsfsi/kernels/detail/pair.hpp"
#include "mpsfsi/kernels/lattice_constants.hpp"
#include "mpsfsi/kernels/weight.hpp"

namespace mpsfsi {
inline namespace MPSFSI_ABI {

// Gradient-correction policies. Both are called the same way:
//   correction.template update<Weight>(x, list, constants);   // once per step
//   correction.apply(i, r_ij)                                  // -> C_i r_ij
// and enter the gradient and divergence as
//   <grad phi>_i = (1/n0) sum_j (phi_j - phi_i) / |r_ij|^2 w_ij C_i r_ij.

// The null object: C_i = d I, which turns the formula above into the standard MPS gradient
// (d/n0) sum_j (phi_j - phi_i) r_ij / |r_ij|^2 w_ij of Koshizuka & Oka.
template <int Dim, class Scalar = double>
class NoGradientCorrection {
 public:
  template <class Weight>
  void update(const VecArray<Dim, Scalar>&, const BasicNeighborList<Scalar>&, const MpsConstants<Scalar>&) {}
  Vec<Dim, Scalar> apply(std::size_t, const Vec<Dim, Scalar>& r) const { return Scalar(Dim) * r; }
  bool is_corrected(std::size_t) const { return false; }
};

// Khayyer & Gotoh 2011: C_i = A_i^-1 with the moment matrix
//   A_i = (1/n0) sum_j w_ij (r_ij (x) r_ij) / |r_ij|^2,
// which makes the gradient exact for linear fields wherever A_i is invertible. For a full,
// isotropic neighbourhood A_i = I/d, so C_i = d I. Where A_i is near-singular (a particle with
// few neighbours at a free surface or in a splash), the particle falls back to C_i = d I: its
// smallest eigenvalue must be at least `min_eigenvalue_ratio / d`.
template <int Dim, class Scalar = double>
class KhayyerGotohCorrection {
 public:
  explicit KhayyerGotohCorrection(Scalar min_eigenvalue_ratio = Scalar(0.1))
      : min_eigenvalue_ratio_(min_eigenvalue_ratio) {}

  template <class Weight>
  void update(const VecArray<Dim, Scalar>& x, const BasicNeighborList<Scalar>& list,
              const MpsConstants<Scalar>& c) {
    check_weight<Weight>();
    detail::require_list_rows(list, x.size(), "KhayyerGotohCorrection::update");
    detail::require_positive_constants(c.re, c.n0, "KhayyerGotohCorrection::update");
    matrix_.resize(x.size());
    corrected_.resize(x.size());
    const Scalar floor = min_eigenvalue_ratio_ / Scalar(Dim);
    MPSFSI_OMP(parallel for schedule(static))
    for (std::int64_t ii = 0; ii < static_cast<std::int64_t>(x.size()); ++ii) {
      const auto i = static_cast<std::size_t>(ii);
      Mat<Dim, Scalar> a = Mat<Dim, Scalar>::Zero();
      for (Offset k = list.begin(i); k < list.end(i); ++k) {
        const Vec<Dim, Scalar> r = x[static_cast<std::size_t>(list.indices[k])] - x[i];
        const Scalar d = detail::pair_distance(list, k, r);
        const Scalar w = Weight::value(d, c.re);
        if (w == Scalar(0) || !(d > Scalar(0))) continue;  // coincident particles: no direction
        a.noalias() += (w / (d * d)) * (r * r.transpose());
      }
      a /= c.n0;
      Eigen::SelfAdjointEigenSolver<Mat<Dim, Scalar>> eig;
      eig.computeDirect(a, Eigen::EigenvaluesOnly);
      const bool ok = eig.eigenvalues()[0] >= floor;
      corrected_[i] = ok ? 1 : 0;
      matrix_[i] = ok ? Mat<Dim, Scalar>(a.inverse()) : Mat<Dim, Scalar>(Scalar(Dim) * Mat<Dim, Scalar>::Identity());
    }
  }

  Vec<Dim, Scalar> apply(std::size_t i, const Vec<Dim, Scalar>& r) const { return matrix_[i] * r; }
  bool is_corrected(std::size_t i) const { return corrected_[i] != 0; }
  const MatArray<Dim, Scalar>& matrices() const { return matrix_; }
  Scalar min_eigenvalue_ratio() const { return min_eigenvalue_ratio_; }

 private:
  Scalar min_eigenvalue_ratio_;
  MatArray<Dim, Scalar> matrix_;
  std::vector<std::uint8_t> corrected_;
};

}  // namespace MPSFSI_ABI
}  // namespace mpsfsi
