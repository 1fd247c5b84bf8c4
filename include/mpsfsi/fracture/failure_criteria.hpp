// SPDX-License-Identifier: BSD-3-Clause
#pragma once

#include <cmath>
#include <limits>

#include <Eigen/Eigenvalues>

#include "mpsfsi/core/abi.hpp"
#include "mpsfsi/core/types.hpp"

namespace mpsfsi {
inline namespace MPSFSI_ABI {

// A failure model (the `failure` policy of ElasticSolver) is an object the solver holds, built
// from the parameters the user passes to the solver's constructor. It provides
//   static constexpr bool enabled;
//   template <int Dim, class Scalar>
//   Scalar principal(const Mat<Dim, Scalar>& sigma, Vec<Dim, Scalar>& direction) const;  // or static
// returning the stress the criterion compares with the particle's strength (for the maximum
// normal stress criterion, sigma_1, the largest normal stress over all directions) and, in
// `direction`, the unit normal of the plane it would crack on (n_c). A particle fails when the
// value reaches its strength (eq 27). `principal` runs inside a parallel loop over particles: it
// must not modify shared state. Optionally (strength.hpp)
//   void assign_strengths(const StrengthSetup&, std::vector<double>& strength) const;
// sets each particle's strength once, when the solver is built; without it every particle has
// SolidParameters::tensile_strength. The criteria below carry no parameters and cost what a
// static function does.

// Null object: nothing ever fails (the solver skips the check entirely).
struct NoFailure {
  static constexpr bool enabled = false;
  template <int Dim, class Scalar>
  static Scalar principal(const Mat<Dim, Scalar>&, Vec<Dim, Scalar>& direction) {
    direction = Vec<Dim, Scalar>::UnitX();
    return -std::numeric_limits<Scalar>::infinity();
  }
};

// sigma_1 as the largest eigenvalue of the stress tensor and its eigenvector (the paper's
// "first principal stress"): closed form in 2D, Eigen's self-adjoint solver in 3D.
// A principal direction has no sign, but the crack-plane rule (crack_plane.hpp) puts the cut on
// the normal's - side, so the sign chooses which neighbour column a crack opens towards. Both
// dimensions return the same convention: the first non-zero component is positive (n_x >= 0;
// the 2D closed form gives it with theta in (-pi/2, pi/2]; Eigen's sign is arbitrary, so the 3D
// vector is flipped to it).
struct MaxPrincipalStress {
  static constexpr bool enabled = true;
  template <int Dim, class Scalar>
  static Scalar principal(const Mat<Dim, Scalar>& sigma, Vec<Dim, Scalar>& direction) {
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
      Eigen::SelfAdjointEigenSolver<Mat<Dim, Scalar>> eig(Scalar(0.5) * (sigma + sigma.transpose()));
      direction = eig.eigenvectors().col(Dim - 1);  // eigenvalues ascend
      for (int k = 0; k < Dim; ++k) {
        if (direction[k] == Scalar(0)) continue;
        if (direction[k] < Scalar(0)) direction = -direction;
        break;
      }
      return eig.eigenvalues()[Dim - 1];
    }
  }
};

// The paper's angle solution in 2D (eqs 28-33): the normal stress on a plane at angle alpha is
//   sigma_n(alpha) = cos^2 a sigma_xx + 2 cos a sin a sigma_xy + sin^2 a sigma_yy   (eq 29),
// stationary where chi = cos^2 alpha solves chi^2 - chi + B/(A + 4B) = 0              (eq 32)
//   chi = 1/2 +- 1/2 sqrt(1 - 4B/(A + 4B)),  A = (sigma_xx - sigma_yy)^2, B = sigma_xy^2  (eq 33).
// Eq 29 takes sin alpha = +sqrt(1 - cos^2 alpha); both signs of sin alpha (and both roots) are
// tried here and the largest sigma_n kept, which is what "maximum normal stress" requires. For an
// isotropic stress (A + 4B = 0) every direction is principal; x is returned.
struct MaxNormalStressAngle {
  static constexpr bool enabled = true;
  template <int Dim, class Scalar>
  static Scalar principal(const Mat<Dim, Scalar>& sigma, Vec<Dim, Scalar>& direction) {
    static_assert(Dim == 2, "MaxNormalStressAngle is the paper's 2D solution; use MaxPrincipalStress in 3D");
    const Scalar sxx = sigma(0, 0), syy = sigma(1, 1), sxy = Scalar(0.5) * (sigma(0, 1) + sigma(1, 0));
    const Scalar a = (sxx - syy) * (sxx - syy), b = sxy * sxy;
    direction = Vec<2, Scalar>::UnitX();
    if (!(a + 4 * b > 0)) return sxx;
    const Scalar root = Scalar(0.5) * std::sqrt(std::max(Scalar(0), Scalar(1) - 4 * b / (a + 4 * b)));
    Scalar best = -std::numeric_limits<Scalar>::infinity();
    for (const Scalar chi : {Scalar(0.5) + root, Scalar(0.5) - root}) {
      const Scalar c = std::sqrt(std::max(Scalar(0), chi)), s = std::sqrt(std::max(Scalar(0), Scalar(1) - chi));
      for (const Scalar sign : {Scalar(1), Scalar(-1)}) {
        const Scalar value = c * c * sxx + 2 * c * sign * s * sxy + s * s * syy;  // eq 29
        if (value > best) {
          best = value;
          direction = Vec<2, Scalar>(c, sign * s);
        }
      }
    }
    return best;
  }
};

}  // namespace MPSFSI_ABI
}  // namespace mpsfsi
