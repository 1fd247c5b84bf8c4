// SPDX-License-Identifier: BSD-3-Clause
#pragma once

#include <cmath>
#include <limits>

#include <Eigen/Eigenvalues>

#include "mpsfsi/core/abi.hpp"
#include "mpsfsi/core/types.hpp"
#include "mpsfsi/solid/failure_slot.hpp"
#include "mpsfsi/solid/principal_stress.hpp"

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
// SolidParameters::tensile_strength. And optionally
//   template <int Dim, class Scalar> Scalar upper_bound(const Mat<Dim, Scalar>& sigma) const;  // or static
// a value never below principal()'s, cheaper to compute: where it is below the particle's
// strength the particle cannot fail, and the check leaves principal() for the output field
// (FractureProcess). A model whose bound is also a convex function of sigma may say so,
//   static constexpr bool upper_bound_is_convex = true;
// and the check then averages the read-out (failure_stress.hpp) only where the highest bound over
// a particle's neighbourhood reaches its strength. The criteria below carry no parameters and
// cost what a static function does.

// NoFailure, the null object (nothing ever fails), is solid/failure_slot.hpp's: the default of
// every solid, with or without this folder.

// The maximum principal stress criterion: sigma_1 and its direction (max_principal_stress,
// solid/principal_stress.hpp, which also fills ElasticSolver's `max_principal_stress` output).
struct MaxPrincipalStress {
  static constexpr bool enabled = true;
  template <int Dim, class Scalar>
  static Scalar principal(const Mat<Dim, Scalar>& sigma, Vec<Dim, Scalar>& direction) {
    return max_principal_stress<Dim, Scalar>(sigma, direction);
  }
  // sigma_1 <= m + sqrt((d-1)/d) |s|_F, m = tr(sigma)/d and s = sigma - m I the deviator: the
  // eigenvalues s_k of s sum to zero, and the largest of d numbers with zero sum and sum of
  // squares |s|_F^2 is at most sqrt((d-1)/d) |s|_F (equality when the other d-1 are equal; in 2D
  // the bound is Mohr's radius, exact). In 3D it costs a tenth of the eigen-decomposition. The
  // last term covers the round-off of both evaluations. Convex: m is linear in sigma, |s|_F is a
  // norm of a linear function of sigma, and |m| is convex.
  static constexpr bool upper_bound_is_convex = true;
  template <int Dim, class Scalar>
  static Scalar upper_bound(const Mat<Dim, Scalar>& sigma) {
    const Scalar mean = sigma.trace() / Dim;
    const Mat<Dim, Scalar> symmetric = Scalar(0.5) * (sigma + sigma.transpose());
    const Scalar deviator = (symmetric - mean * Mat<Dim, Scalar>::Identity()).norm();
    return mean + std::sqrt(Scalar(Dim - 1) / Dim) * deviator + Scalar(1e-12) * (std::abs(mean) + deviator);
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
