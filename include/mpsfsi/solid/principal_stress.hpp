// SPDX-License-Identifier: BSD-3-Clause
#pragma once

#include <cmath>

#include <Eigen/Eigenvalues>

#include "mpsfsi/core/abi.hpp"
#include "mpsfsi/core/types.hpp"

namespace mpsfsi {
inline namespace MPSFSI_ABI {

// sigma_1, the largest eigenvalue of a stress tensor (the paper's "first principal stress"), and
// its unit eigenvector in `direction`: closed form in 2D, Eigen's self-adjoint solver in 3D.
// A principal direction has no sign, but the crack-plane rule (crack_plane.hpp) puts the cut on
// the normal's - side, so the sign chooses which neighbour column a crack opens towards. Both
// dimensions return the same convention: the first non-zero component is positive (n_x >= 0;
// the 2D closed form gives it with theta in (-pi/2, pi/2]; Eigen's sign is arbitrary, so the 3D
// vector is flipped to it).
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

}  // namespace MPSFSI_ABI
}  // namespace mpsfsi
