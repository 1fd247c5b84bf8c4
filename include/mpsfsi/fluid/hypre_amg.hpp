// SPDX-License-Identifier: BSD-3-Clause
#pragma once

// Algebraic multigrid for the PPE through hypre: needs hypre (Debian: libhypre-dev) and the
// target mpsfsi::hypre, which CMake provides when hypre is found. Not included by mpsfsi.hpp.

#include <HYPRE.h>
#include <HYPRE_parcsr_ls.h>
#include <mpi.h>

#include <chrono>
#include <cmath>
#include <cstdlib>
#include <vector>

#include "mpsfsi/core/abi.hpp"
#include "mpsfsi/fluid/linear_solver.hpp"

namespace mpsfsi {
inline namespace MPSFSI_ABI {

namespace detail {

// MPI must be running before hypre is used. A program that initialised MPI itself keeps
// control of it; otherwise MPI (and hypre) are started on first use and finalised at exit.
inline void ensure_hypre_ready() {
  static const bool ready = [] {
    int initialized = 0;
    MPI_Initialized(&initialized);
    if (!initialized) {
      MPI_Init(nullptr, nullptr);
      std::atexit([] {
        int finalized = 0;
        MPI_Finalized(&finalized);
        if (!finalized) MPI_Finalize();
      });
    }
#if defined(HYPRE_RELEASE_NUMBER) && HYPRE_RELEASE_NUMBER >= 22000
    HYPRE_Init();
#endif
    return true;
  }();
  (void)ready;
}

// CG preconditioned by one V-cycle of BoomerAMG on an assembled ParCSR system, to
// |r| <= tolerance |b| in the 2-norm, from the start x holds; hypre's defaults except the
// strength threshold (hypre's default 0.25) and the levels of aggressive coarsening (default 0).
// `setup_seconds`, if given, receives the wall time of the AMG set-up.
inline SolveReport boomeramg_pcg(MPI_Comm comm, HYPRE_ParCSRMatrix a, HYPRE_ParVector b, HYPRE_ParVector x, double tolerance,
                                 int max_iterations, double strong_threshold = 0.25, int aggressive_levels = 0,
                                 double* setup_seconds = nullptr) {
  HYPRE_Solver amg, pcg;
  HYPRE_BoomerAMGCreate(&amg);
  HYPRE_BoomerAMGSetPrintLevel(amg, 0);
  HYPRE_BoomerAMGSetMaxIter(amg, 1);
  HYPRE_BoomerAMGSetTol(amg, 0.0);
  HYPRE_BoomerAMGSetStrongThreshold(amg, strong_threshold);
  HYPRE_BoomerAMGSetAggNumLevels(amg, aggressive_levels);
  HYPRE_ParCSRPCGCreate(comm, &pcg);
  HYPRE_PCGSetTol(pcg, tolerance);
  HYPRE_PCGSetMaxIter(pcg, max_iterations);
  HYPRE_PCGSetTwoNorm(pcg, 1);
  HYPRE_PCGSetLogging(pcg, 1);
  HYPRE_PCGSetPrintLevel(pcg, 0);
  HYPRE_PCGSetPrecond(pcg, reinterpret_cast<HYPRE_PtrToSolverFcn>(HYPRE_BoomerAMGSolve),
                      reinterpret_cast<HYPRE_PtrToSolverFcn>(HYPRE_BoomerAMGSetup), amg);
  const auto start = std::chrono::steady_clock::now();
  HYPRE_ParCSRPCGSetup(pcg, a, b, x);
  if (setup_seconds) *setup_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  HYPRE_ParCSRPCGSolve(pcg, a, b, x);
  HYPRE_Int iterations = 0;
  HYPRE_Real residual = 1;
  HYPRE_PCGGetNumIterations(pcg, &iterations);
  HYPRE_PCGGetFinalRelativeResidualNorm(pcg, &residual);
  HYPRE_ParCSRPCGDestroy(pcg);
  HYPRE_BoomerAMGDestroy(amg);
  return SolveReport{std::isfinite(residual) && residual <= tolerance, static_cast<int>(iterations),
                     static_cast<double>(residual)};
}

}  // namespace detail

// Conjugate gradient preconditioned by one V-cycle of BoomerAMG (hypre's defaults: HMIS
// coarsening, extended+i interpolation, hybrid symmetric Gauss-Seidel smoothing). The AMG
// hierarchy is rebuilt for every solve, since the PPE matrix changes every step. Each process
// solves its own system (MPI_COMM_SELF), so the policy also works inside an MPI program.
// Converged when |r| <= tolerance |b| in the 2-norm, as JacobiCg.
class HypreAmgCg {
 public:
  HypreAmgCg() { detail::ensure_hypre_ready(); }

  SolveReport solve(const PpeMatrix& a, const PpeVector& b, PpeVector& x, double tolerance, int max_iterations) {
    const auto n = static_cast<HYPRE_Int>(a.rows());
    if (x.size() != a.rows()) x = PpeVector::Zero(a.rows());
    if (n == 0) return SolveReport{true, 0, 0.0};
    if (b.norm() == 0) {
      x.setZero();
      return SolveReport{true, 0, 0.0};
    }
    const MPI_Comm comm = MPI_COMM_SELF;
    rows_.resize(static_cast<std::size_t>(n));
    counts_.resize(static_cast<std::size_t>(n));
    for (HYPRE_Int i = 0; i < n; ++i) {
      rows_[static_cast<std::size_t>(i)] = i;
      counts_[static_cast<std::size_t>(i)] = a.outerIndexPtr()[i + 1] - a.outerIndexPtr()[i];
    }

    HYPRE_IJMatrix ij_a;
    HYPRE_IJMatrixCreate(comm, 0, n - 1, 0, n - 1, &ij_a);
    HYPRE_IJMatrixSetObjectType(ij_a, HYPRE_PARCSR);
    HYPRE_IJMatrixSetRowSizes(ij_a, counts_.data());
    HYPRE_IJMatrixInitialize(ij_a);
    HYPRE_IJMatrixSetValues(ij_a, n, counts_.data(), rows_.data(), a.innerIndexPtr(), a.valuePtr());
    HYPRE_IJMatrixAssemble(ij_a);
    HYPRE_ParCSRMatrix par_a;
    HYPRE_IJMatrixGetObject(ij_a, reinterpret_cast<void**>(&par_a));

    HYPRE_IJVector ij_b, ij_x;
    make_vector(comm, n, b.data(), ij_b);
    make_vector(comm, n, x.data(), ij_x);  // the warm start
    HYPRE_ParVector par_b, par_x;
    HYPRE_IJVectorGetObject(ij_b, reinterpret_cast<void**>(&par_b));
    HYPRE_IJVectorGetObject(ij_x, reinterpret_cast<void**>(&par_x));

    const SolveReport report = detail::boomeramg_pcg(comm, par_a, par_b, par_x, tolerance, max_iterations);
    HYPRE_IJVectorGetValues(ij_x, n, rows_.data(), x.data());

    HYPRE_IJVectorDestroy(ij_x);
    HYPRE_IJVectorDestroy(ij_b);
    HYPRE_IJMatrixDestroy(ij_a);
    return report;
  }

 private:
  void make_vector(MPI_Comm comm, HYPRE_Int n, const double* values, HYPRE_IJVector& v) {
    HYPRE_IJVectorCreate(comm, 0, n - 1, &v);
    HYPRE_IJVectorSetObjectType(v, HYPRE_PARCSR);
    HYPRE_IJVectorInitialize(v);
    HYPRE_IJVectorSetValues(v, n, rows_.data(), values);
    HYPRE_IJVectorAssemble(v);
  }

  std::vector<HYPRE_BigInt> rows_;
  std::vector<HYPRE_Int> counts_;
};

}  // namespace MPSFSI_ABI
}  // namespace mpsfsi
