// SPDX-License-Identifier: BSD-3-Clause
#pragma once

#include <Eigen/IterativeLinearSolvers>
#include <Eigen/SparseCore>
#include <cmath>
#include <cstdint>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "mpsfsi/core/abi.hpp"
#include "mpsfsi/core/parallel.hpp"

#include "mpsfsi/core/error.hpp"

namespace mpsfsi {
inline namespace MPSFSI_ABI {

// Outcome of one linear solve; FluidSolver reports a solve that did not converge.
struct SolveReport {
  bool converged = false;
  int iterations = 0;
  double relative_residual = 0;
};

// Linear-solver policies for the symmetric positive definite PPE matrix (row-major CSR). Each
// has  SolveReport solve(const Matrix& A, const Vector& b, Vector& x, double tol, int max_iter)
// with x holding the initial guess (the last pressure: a warm start) on entry. A policy may also
// have solve_same_matrix with the same arguments, for a matrix equal to the last solve's, which
// FluidSolver calls in a step repeated from its start (SsorCg: its set-up reused).
using PpeMatrix = Eigen::SparseMatrix<double, Eigen::RowMajor, int>;
using PpeVector = Eigen::VectorXd;

namespace detail {

template <class S, class = void>
struct has_solve_same_matrix : std::false_type {};
template <class S>
struct has_solve_same_matrix<S, std::void_t<decltype(std::declval<S&>().solve_same_matrix(
                                    std::declval<const PpeMatrix&>(), std::declval<const PpeVector&>(),
                                    std::declval<PpeVector&>(), 0.0, 0))>> : std::true_type {};

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

// Conjugate gradient with a Jacobi (diagonal) preconditioner, written for the PPE: three
// OpenMP loops per iteration (the product fused with p.Ap; the updates of x, r and z fused with
// r.z and r.r; the new direction), no allocation once the work vectors have their size. (One
// persistent parallel region with barriers instead was measured slower on 1 and 2 threads.)
// Converged when |r| <= tolerance |b|, r being the recursively updated residual (as Eigen's CG).
class JacobiCg {
 public:
  SolveReport solve(const PpeMatrix& a, const PpeVector& b, PpeVector& x, double tolerance, int max_iterations) {
    const auto n = static_cast<std::int64_t>(a.rows());
    if (x.size() != a.rows()) x = PpeVector::Zero(a.rows());
    // The five work vectors share one block, each starting 3 cache lines further into a 4 KiB
    // page than the last: separately allocated, they can start at the same offset in a page, and
    // the fused loops, which stream all of them, then stall on 4K aliasing (measured: +25 % on
    // the dam-break step's solve with one allocation pattern against another).
    const std::size_t stride = (static_cast<std::size_t>(n) + 511) / 512 * 512 + 24;
    work_.resize(5 * stride + 8);
    double* base = work_.data();
    double* r = base;
    double* z = base + stride;
    double* p = base + 2 * stride;
    double* q = base + 3 * stride;
    double* dinv = base + 4 * stride;
    const int* outer = a.outerIndexPtr();
    const int* col = a.innerIndexPtr();
    const double* val = a.valuePtr();
    double bb = 0, rz = 0, rr = 0;
    bool positive_diagonal = true;
    MPSFSI_OMP(parallel for schedule(static) reduction(+ : bb, rz, rr) reduction(&& : positive_diagonal))
    for (std::int64_t i = 0; i < n; ++i) {
      double ax = 0, diag = 0;
      for (int k = outer[i]; k < outer[i + 1]; ++k) {
        ax += val[k] * x[col[k]];
        if (col[k] == i) diag = val[k];
      }
      positive_diagonal = positive_diagonal && diag > 0;
      dinv[i] = diag > 0 ? 1.0 / diag : 1.0;
      r[i] = b[i] - ax;
      z[i] = dinv[i] * r[i];
      p[i] = z[i];
      bb += b[i] * b[i];
      rz += r[i] * z[i];
      rr += r[i] * r[i];
    }
    if (!positive_diagonal) return SolveReport{false, 0, 1.0};
    if (bb == 0) {
      x.setZero();
      return SolveReport{true, 0, 0.0};
    }
    const double threshold = tolerance * tolerance * bb;
    int it = 0;
    while (rr > threshold && it < max_iterations) {
      ++it;
      double pq = 0;
      MPSFSI_OMP(parallel for schedule(static) reduction(+ : pq))
      for (std::int64_t i = 0; i < n; ++i) {
        double s = 0;
        for (int k = outer[i]; k < outer[i + 1]; ++k) s += val[k] * p[col[k]];
        q[i] = s;
        pq += p[i] * s;
      }
      if (!(pq > 0)) break;  // the matrix is not positive definite along p
      const double alpha = rz / pq;
      double rz_new = 0;
      rr = 0;
      MPSFSI_OMP(parallel for schedule(static) reduction(+ : rz_new, rr))
      for (std::int64_t i = 0; i < n; ++i) {
        x[i] += alpha * p[i];
        r[i] -= alpha * q[i];
        z[i] = dinv[i] * r[i];
        rz_new += r[i] * z[i];
        rr += r[i] * r[i];
      }
      const double beta = rz_new / rz;
      rz = rz_new;
      MPSFSI_OMP(parallel for schedule(static))
      for (std::int64_t i = 0; i < n; ++i) p[i] = z[i] + beta * p[i];
    }
    return SolveReport{rr <= threshold, it, std::sqrt(rr / bb)};
  }

 private:
  std::vector<double> work_;
};

// The same with Eigen's ConjugateGradient and DiagonalPreconditioner, for comparison.
class EigenJacobiCg : public detail::EigenCg<Eigen::DiagonalPreconditioner<double>> {};

// Conjugate gradient with an incomplete Cholesky preconditioner: fewer iterations, a serial
// factorisation every step.
class IncompleteCholeskyCg
    : public detail::EigenCg<Eigen::IncompleteCholesky<double, Eigen::Lower, Eigen::AMDOrdering<int>>> {};

}  // namespace MPSFSI_ABI
}  // namespace mpsfsi
