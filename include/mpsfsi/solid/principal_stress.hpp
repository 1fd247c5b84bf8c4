// SPDX-License-Identifier: BSD-3-Clause
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>

#include <Eigen/Geometry>

#include "mpsfsi/core/abi.hpp"
#include "mpsfsi/core/types.hpp"

namespace mpsfsi {
inline namespace MPSFSI_ABI {

namespace detail {

// A unit vector orthogonal to the rows of a singular symmetric 3x3 matrix m of rank 2: the
// largest of the rows' pairwise cross products.
template <class Scalar>
Vec<3, Scalar> null_vector_of_rank_two(const Mat<3, Scalar>& m) {
  const Vec<3, Scalar> cross[3] = {m.row(0).cross(m.row(1)).transpose(), m.row(0).cross(m.row(2)).transpose(),
                                   m.row(1).cross(m.row(2)).transpose()};
  int best = 0;
  for (int k = 1; k < 3; ++k)
    if (cross[k].squaredNorm() > cross[best].squaredNorm()) best = k;
  return cross[best].normalized();
}

// The largest eigenvalue of a symmetric 3x3 matrix and a unit eigenvector, in closed form (the
// criterion reads one per particle per step; an iterative solver costs four times more).
// The matrix is first scaled by its largest entry. With m = tr(A)/3, B = A - m I,
// p = sqrt(|B|^2 / 6) and r = det(B/p)/2 in [-1, 1], the roots of the characteristic cubic are
// m + 2 p cos((acos(r) + 2 pi k)/3), k = 0, 1, 2 (Smith 1961), the largest at k = 0 and the
// smallest at k = 1. For r >= 0 the largest is at least 1.7 p above the others, for r <= 0 the
// smallest as far below them, so one of the two is always well separated and its eigenvector,
// orthogonal to the rows of A - lambda I, is accurate to round-off:
// - r >= 0: that is sigma_1's vector; the value is then its Rayleigh quotient v^T A v;
// - r < 0: it is sigma_3's vector v3, and sigma_1 with its vector come from Mohr's circle of A
//   restricted to the plane orthogonal to v3, which stays exact where sigma_1 and sigma_2 come
//   together (there the cubic's trigonometric form alone loses half the digits).
// The cost: one acos and one cos (about 1.6e-7 s a tensor here, against 3.5e-7 s for Eigen's
// iterative solver; docs/performance.md).
template <class Scalar>
Scalar largest_symmetric_eigenpair(const Mat<3, Scalar>& a, Vec<3, Scalar>& v) {
  const Scalar scale = a.cwiseAbs().maxCoeff();
  v = Vec<3, Scalar>::UnitX();
  if (scale == 0) return 0;
  if (!std::isfinite(scale)) return std::numeric_limits<Scalar>::quiet_NaN();  // a NaN fails no test
  const Mat<3, Scalar> s = a / scale;
  const Scalar m = s.trace() / 3;
  const Mat<3, Scalar> b = s - m * Mat<3, Scalar>::Identity();
  const Scalar p = std::sqrt(b.squaredNorm() / 6);
  if (!(p > 0)) return m * scale;  // isotropic: every direction is principal
  const Scalar r = std::clamp((b / p).determinant() / 2, Scalar(-1), Scalar(1));
  const Scalar phi = std::acos(r) / 3;
  if (r >= 0) {
    v = null_vector_of_rank_two<Scalar>(b - 2 * p * std::cos(phi) * Mat<3, Scalar>::Identity());
    return v.dot(a * v);
  }
  constexpr Scalar two_thirds_pi = Scalar(2.0943951023931954923);
  const Vec<3, Scalar> v3 = null_vector_of_rank_two<Scalar>(b - 2 * p * std::cos(phi + two_thirds_pi) * Mat<3, Scalar>::Identity());
  int axis = 0;  // the axis v3 leans on least, for a well-conditioned orthonormal pair
  for (int k = 1; k < 3; ++k)
    if (std::abs(v3[k]) < std::abs(v3[axis])) axis = k;
  const Vec<3, Scalar> e1 = v3.cross(Vec<3, Scalar>::Unit(axis)).normalized();
  const Vec<3, Scalar> e2 = v3.cross(e1);
  const Scalar b11 = e1.dot(s * e1), b22 = e2.dot(s * e2), b12 = e1.dot(s * e2);
  const Scalar half_diff = Scalar(0.5) * (b11 - b22);
  const Scalar radius = std::sqrt(half_diff * half_diff + b12 * b12);  // entries of order 1: no overflow
  // The 2x2 eigenvector of the larger root mean + radius, orthogonal to the row of
  // [b - (mean + radius) I] with the larger diagonal entry (no cancellation); e1 where the
  // circle has no radius.
  const Scalar c = half_diff >= 0 ? radius + half_diff : b12;
  const Scalar d = half_diff >= 0 ? b12 : radius - half_diff;
  const Scalar length = std::sqrt(c * c + d * d);
  v = length > 0 ? Vec<3, Scalar>((c * e1 + d * e2) / length) : e1;
  return (Scalar(0.5) * (b11 + b22) + radius) * scale;
}

}  // namespace detail

// sigma_1, the largest eigenvalue of a stress tensor (the paper's "first principal stress"), and
// its unit eigenvector in `direction`, both in closed form (2D: Mohr's circle; 3D:
// detail::largest_symmetric_eigenpair).
// A principal direction has no sign, but the crack-plane rule (crack_plane.hpp) puts the cut on
// the normal's - side, so with CrackSide::fixed_sign (the default) the sign chooses which
// neighbour column a crack opens towards. Both dimensions return the same convention: the first
// non-zero component is positive (n_x >= 0; the 2D closed form gives it with theta in
// (-pi/2, pi/2]; the 3D vector is flipped to it).
template <int Dim, class Scalar>
Scalar max_principal_stress(const Mat<Dim, Scalar>& sigma, Vec<Dim, Scalar>& direction) {
  if constexpr (Dim == 2) {
    const Scalar mean = Scalar(0.5) * (sigma(0, 0) + sigma(1, 1));
    const Scalar half_diff = Scalar(0.5) * (sigma(0, 0) - sigma(1, 1));
    const Scalar shear = Scalar(0.5) * (sigma(0, 1) + sigma(1, 0));
    const Scalar radius = std::hypot(half_diff, shear);  // Mohr's circle
    // Direction angle theta with tan(2 theta) = 2 sigma_xy / (sigma_xx - sigma_yy).
    const Scalar theta = radius > 0 ? Scalar(0.5) * std::atan2(shear, half_diff) : Scalar(0);
    direction = Vec<2, Scalar>(std::cos(theta), std::sin(theta));
    return mean + radius;
  } else {
    const Scalar sigma1 = detail::largest_symmetric_eigenpair<Scalar>(Scalar(0.5) * (sigma + sigma.transpose()), direction);
    for (int k = 0; k < Dim; ++k) {
      if (direction[k] == Scalar(0)) continue;
      if (direction[k] < Scalar(0)) direction = -direction;
      break;
    }
    return sigma1;
  }
}

}  // namespace MPSFSI_ABI
}  // namespace mpsfsi
