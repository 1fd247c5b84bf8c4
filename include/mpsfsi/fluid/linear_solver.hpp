// SPDX-License-Identifier: BSD-3-Clause
#pragma once

#include <Eigen/IterativeLinearSolvers>
#include <Eigen/SparseCore>
#include <string>

#include "mpsfsi/core/error.hpp"

namespace mpsfsi {

// Outcome of one linear solve; FluidSolver reports a solve that did not converge.
struct SolveReport {
  bool converged = false;
  int iterations = 0;
  double relative_residual = 0;
};

// Linear-solver policies for the symmetric positive definite PPE matrix (row-major CSR). Each
// has  SolveReport solve(const Matrix& A, const Vector& b, Vector& x, double tol, int max_iter)
// with x holding the initial guess (the last pressure: a warm start) on entry.
using PpeMatrix = Eigen::SparseMatrix<double, Eigen::RowMajor, int>;
using PpeVector = Eigen::VectorXd;

namespace detail {

template <class Preconditioner>
class EigenCg {
 public:
  SolveReport solve(const PpeMatrix& a, const PpeVector& b, PpeVector& x, double tolerance, int max_iterations) {
    // Lower|Upper lets Eigen's CG use its multi-threaded row-major product.
    Eigen::ConjugateGradient<PpeMatrix, Eigen::Lower | Eigen::Upper, Preconditioner> cg;
    cg.setTolerance(tolerance);
    cg.setMaxIterations(max_iterations);
    cg.compute(a);
    if (cg.info() != Eigen::Success) return SolveReport{false, 0, 1.0};
    x = cg.solveWithGuess(b, x);
    return SolveReport{cg.info() == Eigen::Success, static_cast<int>(cg.iterations()), cg.error()};
  }
};

}  // namespace detail

// Conjugate gradient with a Jacobi (diagonal) preconditioner: cheap per iteration, O(N^0.5)
// iterations in 2D.
class JacobiCg : public detail::EigenCg<Eigen::DiagonalPreconditioner<double>> {};

// Conjugate gradient with an incomplete Cholesky preconditioner: fewer iterations, a serial
// factorisation every step.
class IncompleteCholeskyCg
    : public detail::EigenCg<Eigen::IncompleteCholesky<double, Eigen::Lower, Eigen::AMDOrdering<int>>> {};

}  // namespace mpsfsi
