// SPDX-License-Identifier: BSD-3-Clause
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

#include "mpsfsi/core/error.hpp"
#include "mpsfsi/core/parallel.hpp"
#include "mpsfsi/fluid/linear_solver.hpp"
#include "mpsfsi/fluid/ssor_cg.hpp"
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
  // The reported residual is the recursively updated one; the true one drifts from it by about
  // machine epsilon times the condition number (< 400), far below 1e-10.
  CHECK((b - a * x).norm() <= 2e-10 * b.norm());
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

TEST_CASE("fluid.linear_solver: SSOR CG (Eisenstat), plain and deflated, on one, two and three threads") {
  const int saved = parallel::max_threads();
  for (int threads : {1, 2, 3}) {
    CAPTURE(threads);
    parallel::set_num_threads(threads);
    if (parallel::max_threads() != threads) continue;  // a build without OpenMP
    check_solver<SsorCg>();
    check_solver<DeflatedSsorCg>();
  }
  parallel::set_num_threads(saved);
}

TEST_CASE("fluid.linear_solver: SSOR CG on two threads is SSOR in the twisted order, no coupling dropped") {
  // 30 x 30 Poisson, rows numbered along x: thread 0 takes grid rows 0-14, thread 1 rows 15-29.
  // The separator is grid row 15 (coupled to row 14); the order is rows 0-14 forward, rows 29
  // down to 16 (every x backwards too), then row 15. One-thread SSOR-CG on the matrix renumbered
  // that way must run the same iterations to the same answer.
  const int m = 30, n = m * m;
  const PpeMatrix a = test::poisson_2d(m);
  PpeVector b(n);
  for (int i = 0; i < n; ++i) b[i] = 1.0 + std::cos(0.3 * i);
  std::vector<int> position(n);
  for (int i = 0; i < n; ++i) {
    const int row = i / m;
    position[i] = row < m / 2 ? i : row == m / 2 ? n - m + (i - n / 2) : n / 2 + (n - 1 - i);
  }
  std::vector<Eigen::Triplet<double>> entries;
  for (int i = 0; i < n; ++i)
    for (PpeMatrix::InnerIterator e(a, i); e; ++e) entries.emplace_back(position[i], position[e.col()], e.value());
  PpeMatrix renumbered(n, n);
  renumbered.setFromTriplets(entries.begin(), entries.end());
  PpeVector b_renumbered(n);
  for (int i = 0; i < n; ++i) b_renumbered[position[i]] = b[i];

  const int saved = parallel::max_threads();
  parallel::set_num_threads(2);
  if (parallel::max_threads() == 2) {  // a build with OpenMP
    SsorCg ssor;
    PpeVector x = PpeVector::Zero(n);
    const SolveReport two = ssor.solve(a, b, x, 1e-10, 10000);
    parallel::set_num_threads(1);
    PpeVector y = PpeVector::Zero(n);
    const SolveReport one = ssor.solve(renumbered, b_renumbered, y, 1e-10, 10000);
    MESSAGE("SSOR-CG on 30 x 30 Poisson: two threads ", two.iterations, " iterations, one thread in the twisted order ",
            one.iterations);
    REQUIRE(two.converged);
    REQUIRE(one.converged);
    // The same Krylov process up to round-off: the same count, the same answer far within the
    // tolerance (kappa < 400 times 1e-10 bounds the difference of any two converged answers).
    CHECK(two.iterations == one.iterations);
    double difference = 0;
    for (int i = 0; i < n; ++i) difference = std::max(difference, std::abs(x[i] - y[position[i]]));
    CHECK(difference <= 400 * 1e-10 * x.cwiseAbs().maxCoeff());
  }
  parallel::set_num_threads(saved);
}

TEST_CASE("fluid.linear_solver: SSOR CG needs fewer iterations than Jacobi CG, for the same answer") {
  const int m = 60, n = m * m;
  const PpeMatrix a = test::poisson_2d(m);
  PpeVector b(n);
  for (int i = 0; i < n; ++i) b[i] = 1.0 + std::cos(0.3 * i);
  const int saved = parallel::max_threads();
  parallel::set_num_threads(1);
  JacobiCg jacobi;
  PpeVector xj = PpeVector::Zero(n);
  const SolveReport rj = jacobi.solve(a, b, xj, 1e-10, 10000);
  SsorCg ssor;
  PpeVector xs = PpeVector::Zero(n);
  const SolveReport rs = ssor.solve(a, b, xs, 1e-10, 10000);
  parallel::set_num_threads(saved);
  REQUIRE(rj.converged);
  REQUIRE(rs.converged);
  // For the Poisson matrix, CG iterations grow as sqrt(kappa) ~ m with Jacobi and, with SSOR at a
  // good omega, as sqrt(m) (Axelsson & Barker 1984); at m = 60 that is several times fewer.
  MESSAGE("Jacobi-CG ", rj.iterations, " iterations, SSOR-CG (omega 1.6) ", rs.iterations);
  CHECK(rs.iterations * 2 < rj.iterations);
  // Both answers within kappa (< 1500 at m = 60) times the tolerance of each other.
  CHECK((xs - xj).norm() <= 2 * 1500 * 1e-10 * xj.norm());
}

TEST_CASE("fluid.linear_solver: SSOR CG deflated by aggregates needs fewer iterations, for the same answer") {
  const int m = 60, n = m * m;
  const PpeMatrix a = test::poisson_2d(m);
  PpeVector b(n);
  for (int i = 0; i < n; ++i) b[i] = 1.0 + std::cos(0.3 * i);
  const int saved = parallel::max_threads();
  for (int threads : {1, 2}) {
    CAPTURE(threads);
    parallel::set_num_threads(threads);
    if (parallel::max_threads() != threads) continue;
    SsorCg plain;
    DeflatedSsorCg deflated;
    PpeVector xp = PpeVector::Zero(n), xd = PpeVector::Zero(n);
    const SolveReport rp = plain.solve(a, b, xp, 1e-10, 10000);
    const SolveReport rd = deflated.solve(a, b, xd, 1e-10, 10000);
    MESSAGE("60 x 60 Poisson, ", threads, " thread(s): SSOR-CG ", rp.iterations, " iterations, deflated ", rd.iterations);
    REQUIRE(rp.converged);
    REQUIRE(rd.converged);
    // The reported residual is the true one of the answer returned (P b - P A x^ = b - A x).
    CHECK((b - a * xd).norm() <= 2e-10 * b.norm());
    // Both answers within kappa (< 1500 at m = 60) times the tolerance of each other.
    CHECK((xd - xp).norm() <= 2 * 1500 * 1e-10 * xp.norm());
    CHECK(rd.iterations < rp.iterations);
  }
  parallel::set_num_threads(saved);
}

TEST_CASE("fluid.linear_solver: deflated SSOR CG solves a right-hand side from the coarse space without iterating") {
  // 1D Poisson: the greedy aggregation pairs the rows (row 0 takes row 1, row 2 takes row 3, ...).
  // For x = Z y, piecewise constant on the pairs, b = A x is in the range of AZ: the projected
  // residual P b vanishes and the answer is the coarse part Z E^-1 Z^T b alone, which must be x.
  const int n = 40;
  std::vector<Eigen::Triplet<double>> entries;
  for (int i = 0; i < n; ++i) {
    entries.emplace_back(i, i, 2.0);
    if (i > 0) entries.emplace_back(i, i - 1, -1.0);
    if (i + 1 < n) entries.emplace_back(i, i + 1, -1.0);
  }
  PpeMatrix a(n, n);
  a.setFromTriplets(entries.begin(), entries.end());
  PpeVector exact(n);
  for (int i = 0; i < n; ++i) exact[i] = 1.0 + std::sin(0.7 * (i / 2));
  const PpeVector b = a * exact;
  const int saved = parallel::max_threads();
  for (int threads : {1, 2}) {
    CAPTURE(threads);
    parallel::set_num_threads(threads);
    if (parallel::max_threads() != threads) continue;
    DeflatedSsorCg solver;
    PpeVector x = PpeVector::Zero(n);
    const SolveReport r = solver.solve(a, b, x, 1e-12, 100);
    CHECK(r.converged);
    CHECK(r.iterations == 0);
    // kappa(E) < 4 (n/2)^2 / pi^2 ~ 160 bounds the round-off of the coarse solve.
    CHECK((x - exact).norm() <= 1e-12 * exact.norm());
    // A right-hand side outside the coarse space still needs iterations, and converges.
    PpeVector c = b;
    c[7] += 1.0;
    PpeVector y = PpeVector::Zero(n);
    const SolveReport s = solver.solve(a, c, y, 1e-10, 100);
    CHECK(s.converged);
    CHECK(s.iterations > 0);
    CHECK((c - a * y).norm() <= 2e-10 * c.norm());
  }
  parallel::set_num_threads(saved);
}

// A fluid step repeated from its start solves the same matrix with a new right-hand side
// (FluidSolver::snapshot_restored); solve_same_matrix keeps the last solve's set-up for it, and
// must give what a solver that sets up afresh gives, to the bit.
template <class Solver>
void check_same_matrix() {
  const int m = 40, n = m * m;
  const PpeMatrix a = test::poisson_2d(m);
  PpeVector b1(n), b2(n);
  for (int i = 0; i < n; ++i) {
    b1[i] = 1.0 + std::cos(0.3 * i);
    b2[i] = 1.0 + std::sin(0.2 * i);
  }
  Solver reusing, fresh;
  PpeVector x1 = PpeVector::Zero(n);
  REQUIRE(reusing.solve(a, b1, x1, 1e-10, 10000).converged);
  PpeVector x_reused = x1, x_fresh = x1;
  const SolveReport r_reused = reusing.solve_same_matrix(a, b2, x_reused, 1e-10, 10000);
  const SolveReport r_fresh = fresh.solve(a, b2, x_fresh, 1e-10, 10000);
  REQUIRE(r_reused.converged);
  CHECK(r_reused.iterations == r_fresh.iterations);
  CHECK(r_reused.relative_residual == r_fresh.relative_residual);
  CHECK((x_reused.array() == x_fresh.array()).all());
  // Without a set-up of its own (a fresh object), it sets up as solve() does.
  Solver first_call;
  PpeVector x_first = x1;
  const SolveReport r_first = first_call.solve_same_matrix(a, b2, x_first, 1e-10, 10000);
  CHECK(r_first.iterations == r_fresh.iterations);
  CHECK((x_first.array() == x_fresh.array()).all());
}

TEST_CASE("fluid.linear_solver: SSOR CG on the last solve's matrix reuses its set-up, for the same answer") {
  const int saved = parallel::max_threads();
  for (int threads : {1, 2}) {
    CAPTURE(threads);
    parallel::set_num_threads(threads);
    if (parallel::max_threads() != threads) continue;
    check_same_matrix<SsorCg>();
    check_same_matrix<DeflatedSsorCg>();
  }
  parallel::set_num_threads(saved);
  static_assert(detail::has_solve_same_matrix<SsorCg>::value && !detail::has_solve_same_matrix<JacobiCg>::value);
}

TEST_CASE("fluid.linear_solver: SSOR CG rejects bad input clearly") {
  PpeMatrix a = test::poisson_2d(4);
  const PpeVector b = PpeVector::Ones(16);
  PpeVector x;
  SsorCg solver;
  solver.omega = 2.0;
  CHECK_THROWS_AS(solver.solve(a, b, x, 1e-8, 100), InvalidInput);
  solver.omega = 1.6;
  // A non-positive diagonal is reported as not converged (not an SPD PPE), as JacobiCg does.
  PpeMatrix bad = a;
  bad.coeffRef(5, 5) = -4.0;
  x = PpeVector::Zero(16);
  CHECK_FALSE(solver.solve(bad, b, x, 1e-8, 100).converged);
  // Rows must list their columns in increasing order.
  PpeMatrix unsorted = a;
  std::swap(unsorted.innerIndexPtr()[0], unsorted.innerIndexPtr()[1]);
  std::swap(unsorted.valuePtr()[0], unsorted.valuePtr()[1]);
  CHECK_THROWS_WITH_AS(solver.solve(unsorted, b, x, 1e-8, 100), doctest::Contains("increasing order"), InvalidInput);
}

TEST_CASE("fluid.linear_solver: a zero right-hand side gives zero") {
  const PpeMatrix a = test::poisson_2d(4);
  PpeVector x = PpeVector::Ones(16);
  JacobiCg solver;
  const SolveReport r = solver.solve(a, PpeVector::Zero(16), x, 1e-8, 100);
  CHECK(r.converged);
  CHECK(x.norm() == 0.0);
  x = PpeVector::Ones(16);
  SsorCg ssor;
  CHECK(ssor.solve(a, PpeVector::Zero(16), x, 1e-8, 100).converged);
  CHECK(x.norm() == 0.0);
}

}  // TEST_SUITE
