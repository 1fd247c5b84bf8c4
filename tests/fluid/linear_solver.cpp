// SPDX-License-Identifier: BSD-3-Clause
#include <doctest/doctest.h>

#include <vector>

#include "mpsfsi/fluid/linear_solver.hpp"
#include "support/poisson.hpp"

using namespace mpsfsi;

namespace {


template <class Solver>
void check_solver() {
  const int m = 30, n = m * m;
  const PpeMatrix a = test::poisson_2d(m);
  // A smooth exact solution; b = A x.
  PpeVector exact(n);
  for (int i = 0; i < n; ++i) exact[i] = std::sin(0.05 * i) + 0.01 * i;
  const PpeVector b = a * exact;
  Solver solver;
  PpeVector x = PpeVector::Zero(n);
  const SolveReport r = solver.solve(a, b, x, 1e-10, 10000);
  CHECK(r.converged);
  CHECK(r.relative_residual <= 1e-10);
  // Condition number ~ 4 (m+1)^2 / pi^2 < 400: the error is bounded by kappa times the residual.
  CHECK((x - exact).norm() <= 1e-10 * 400 * exact.norm());
  // A warm start from the answer needs no iteration.
  const SolveReport again = solver.solve(a, b, x, 1e-6, 10000);
  CHECK(again.iterations <= 1);
  // Too few iterations is reported, not ignored.
  PpeVector y = PpeVector::Zero(n);
  CHECK_FALSE(solver.solve(a, b, y, 1e-12, 2).converged);
}

}  // namespace

TEST_SUITE("fluid") {

TEST_CASE("fluid.linear_solver: Jacobi CG solves an SPD system and reports non-convergence") { check_solver<JacobiCg>(); }
TEST_CASE("fluid.linear_solver: Eigen Jacobi CG, the reference") { check_solver<EigenJacobiCg>(); }
TEST_CASE("fluid.linear_solver: incomplete Cholesky CG") { check_solver<IncompleteCholeskyCg>(); }

TEST_CASE("fluid.linear_solver: a zero right-hand side gives zero") {
  const PpeMatrix a = test::poisson_2d(4);
  PpeVector x = PpeVector::Ones(16);
  JacobiCg solver;
  const SolveReport r = solver.solve(a, PpeVector::Zero(16), x, 1e-8, 100);
  CHECK(r.converged);
  CHECK(x.norm() == 0.0);
}

}  // TEST_SUITE
