// SPDX-License-Identifier: BSD-3-Clause
// BoomerAMG-preconditioned CG (built only when hypre is found).
#include <doctest/doctest.h>

#include <cmath>

#include "mpsfsi/fluid/hypre_amg.hpp"
#include "support/poisson.hpp"

using namespace mpsfsi;

TEST_SUITE("hypre") {

TEST_CASE("hypre.amg: BoomerAMG-PCG matches Jacobi-CG in far fewer iterations") {
  const int m = 100;
  const PpeMatrix a = test::poisson_2d(m);
  PpeVector exact(m * m);
  for (int i = 0; i < m * m; ++i) exact[i] = std::sin(0.01 * i) + 1.0;
  const PpeVector b = a * exact;
  PpeVector x_amg = PpeVector::Zero(m * m), x_cg = PpeVector::Zero(m * m);
  HypreAmgCg amg;
  JacobiCg cg;
  const SolveReport ra = amg.solve(a, b, x_amg, 1e-10, 1000);
  const SolveReport rc = cg.solve(a, b, x_cg, 1e-10, 10000);
  MESSAGE("10^4 unknowns, tolerance 1e-10: BoomerAMG-PCG " << ra.iterations << " iterations, Jacobi-CG " << rc.iterations);
  CHECK(ra.converged);
  CHECK(rc.converged);
  // Condition number of the 2D Poisson matrix < 4 (m+1)^2 / pi^2 = 4.2e3.
  CHECK((x_amg - exact).norm() <= 1e-10 * 4.2e3 * exact.norm());
  CHECK(ra.iterations * 5 < rc.iterations);
  PpeVector y = PpeVector::Zero(m * m);
  CHECK_FALSE(amg.solve(a, b, y, 1e-14, 1).converged);
}

}  // TEST_SUITE
