// SPDX-License-Identifier: BSD-3-Clause
#pragma once

#include <vector>

#include "mpsfsi/fluid/linear_solver.hpp"

namespace mpsfsi::test {

// The 2D five-point Poisson matrix on an m x m grid with Dirichlet boundaries (SPD), in the
// PPE's row-major CSR. Incomplete Cholesky is not exact on it, unlike on a tridiagonal matrix.
inline PpeMatrix poisson_2d(int m) {
  std::vector<Eigen::Triplet<double>> t;
  auto id = [m](int i, int j) { return i * m + j; };
  for (int i = 0; i < m; ++i)
    for (int j = 0; j < m; ++j) {
      t.emplace_back(id(i, j), id(i, j), 4.0);
      if (i > 0) t.emplace_back(id(i, j), id(i - 1, j), -1.0);
      if (i + 1 < m) t.emplace_back(id(i, j), id(i + 1, j), -1.0);
      if (j > 0) t.emplace_back(id(i, j), id(i, j - 1), -1.0);
      if (j + 1 < m) t.emplace_back(id(i, j), id(i, j + 1), -1.0);
    }
  PpeMatrix a(m * m, m * m);
  a.setFromTriplets(t.begin(), t.end());
  return a;
}

}  // namespace mpsfsi::test
