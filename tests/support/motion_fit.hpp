// SPDX-License-Identifier: BSD-3-Clause
#pragma once

#include <cstddef>
#include <vector>

#include <Eigen/Dense>

namespace mpsfsi::test {

// The acceleration c2 of the least-squares parabola x = c0 + c1 t + c2 t^2 / 2 through the
// samples (t_k, x_k): a body's uniform acceleration read from its positions over a window, so
// that the ringing about the uniform motion averages out.
inline double fitted_acceleration(const std::vector<double>& t, const std::vector<double>& x) {
  Eigen::Matrix3d normal = Eigen::Matrix3d::Zero();
  Eigen::Vector3d rhs = Eigen::Vector3d::Zero();
  for (std::size_t k = 0; k < t.size(); ++k) {
    const Eigen::Vector3d row(1, t[k], 0.5 * t[k] * t[k]);
    normal += row * row.transpose();
    rhs += row * x[k];
  }
  return normal.ldlt().solve(rhs)[2];
}

}  // namespace mpsfsi::test
