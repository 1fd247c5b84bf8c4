// SPDX-License-Identifier: BSD-3-Clause
#pragma once

#include <HYPRE.h>
#include <HYPRE_parcsr_ls.h>

#include <chrono>
#include <cmath>
#include <cstdint>
#include <vector>

#include "mpsfsi/core/abi.hpp"
#include "mpsfsi/fluid/hypre_amg.hpp"
#include "mpsfsi/fluid/linear_solver.hpp"
#include "mpsfsi/mpi/communicator.hpp"

namespace mpsfsi {
inline namespace MPSFSI_ABI {

// A symmetric positive definite system distributed by rows: this process holds the rows
// first_row .. first_row + rows() - 1 in CSR form with global column numbers (rows of lower
// ranks first, no gaps).
struct DistributedRows {
  std::int64_t first_row = 0;
  std::vector<std::int64_t> offsets{0};  // rows() + 1 entries
  std::vector<HYPRE_BigInt> columns;
  std::vector<double> values;
  std::vector<double> rhs;
  std::size_t rows() const { return offsets.size() - 1; }
  void clear() {
    offsets.assign(1, 0);
    columns.clear();
    values.clear();
    rhs.clear();
  }
};

// Conjugate gradient preconditioned by one V-cycle of BoomerAMG, over every process of the
// communicator, through hypre's IJ interface and ParCSR matrices. The hierarchy is rebuilt at
// every solve, and its set-up is most of the cost: the MPS Laplacian couples about 30
// neighbours per row in 2D (re = 3.1 l0), and hypre's default coarsening keeps the coarse
// operators dense. A strength threshold of 0.5 and one level of aggressive coarsening cut the
// set-up from 18 to 5 ms a step on the 2D dam break (4,974 unknowns, 2 processes) for 11 CG
// iterations instead of 7: the PPE solve of the step from 24 to 13 ms (docs/scaling.md).
// Otherwise hypre's defaults. Converged when |r| <= tolerance |b| in the global 2-norm.
// Collective.
class ParallelAmgCg {
 public:
  // Wall-clock seconds of the last solve on this process.
  struct Timings {
    double matrix = 0;  // the IJ matrix and vectors (hypre's ParCSR, ghost columns exchanged)
    double setup = 0;   // the BoomerAMG hierarchy
    double solve = 0;   // the CG iterations, the solution copied back and hypre's objects freed
  };

  double strong_threshold = 0.5;  // BoomerAMG's strength threshold (hypre's default: 0.25)
  int aggressive_levels = 1;      // levels with aggressive coarsening (hypre's default: 0)

  ParallelAmgCg() { detail::ensure_hypre_ready(); }

  // x: this process's part of the warm start, overwritten with the solution.
  SolveReport solve(const Communicator& comm, const DistributedRows& a, std::vector<double>& x, double tolerance,
                    int max_iterations) {
    const auto start = std::chrono::steady_clock::now();
    timings_ = Timings{};
    const auto n = static_cast<HYPRE_Int>(a.rows());
    x.resize(a.rows(), 0.0);
    const std::int64_t total = comm.sum(static_cast<std::int64_t>(n));
    double b2 = 0;
    for (const double v : a.rhs) b2 += v * v;
    if (total == 0 || comm.sum(b2) == 0) {
      std::fill(x.begin(), x.end(), 0.0);
      return SolveReport{true, 0, 0.0};
    }
    const auto lower = static_cast<HYPRE_BigInt>(a.first_row);
    const auto upper = static_cast<HYPRE_BigInt>(a.first_row + n - 1);
    rows_.resize(static_cast<std::size_t>(n));
    counts_.resize(static_cast<std::size_t>(n));
    for (HYPRE_Int i = 0; i < n; ++i) {
      rows_[static_cast<std::size_t>(i)] = lower + i;
      counts_[static_cast<std::size_t>(i)] = static_cast<HYPRE_Int>(a.offsets[static_cast<std::size_t>(i) + 1] -
                                                                    a.offsets[static_cast<std::size_t>(i)]);
    }
    HYPRE_IJMatrix ij_a;
    HYPRE_IJMatrixCreate(comm.get(), lower, upper, lower, upper, &ij_a);
    HYPRE_IJMatrixSetObjectType(ij_a, HYPRE_PARCSR);
    HYPRE_IJMatrixSetRowSizes(ij_a, counts_.data());
    HYPRE_IJMatrixInitialize(ij_a);
    if (n > 0) HYPRE_IJMatrixSetValues(ij_a, n, counts_.data(), rows_.data(), a.columns.data(), a.values.data());
    HYPRE_IJMatrixAssemble(ij_a);
    HYPRE_ParCSRMatrix par_a;
    HYPRE_IJMatrixGetObject(ij_a, reinterpret_cast<void**>(&par_a));
    HYPRE_IJVector ij_b, ij_x;
    make_vector(comm, lower, upper, a.rhs.data(), ij_b);
    make_vector(comm, lower, upper, x.data(), ij_x);
    HYPRE_ParVector par_b, par_x;
    HYPRE_IJVectorGetObject(ij_b, reinterpret_cast<void**>(&par_b));
    HYPRE_IJVectorGetObject(ij_x, reinterpret_cast<void**>(&par_x));

    timings_.matrix = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    const SolveReport report = detail::boomeramg_pcg(comm.get(), par_a, par_b, par_x, tolerance, max_iterations,
                                                     strong_threshold, aggressive_levels, &timings_.setup);
    if (n > 0) HYPRE_IJVectorGetValues(ij_x, n, rows_.data(), x.data());
    HYPRE_IJVectorDestroy(ij_x);
    HYPRE_IJVectorDestroy(ij_b);
    HYPRE_IJMatrixDestroy(ij_a);
    timings_.solve =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() - timings_.matrix - timings_.setup;
    return report;
  }

  const Timings& last_timings() const { return timings_; }

 private:
  void make_vector(const Communicator& comm, HYPRE_BigInt lower, HYPRE_BigInt upper, const double* values,
                   HYPRE_IJVector& v) {
    HYPRE_IJVectorCreate(comm.get(), lower, upper, &v);
    HYPRE_IJVectorSetObjectType(v, HYPRE_PARCSR);
    HYPRE_IJVectorInitialize(v);
    if (upper >= lower) HYPRE_IJVectorSetValues(v, static_cast<HYPRE_Int>(upper - lower + 1), rows_.data(), values);
    HYPRE_IJVectorAssemble(v);
  }

  Timings timings_;
  std::vector<HYPRE_BigInt> rows_;
  std::vector<HYPRE_Int> counts_;
};

}  // namespace MPSFSI_ABI
}  // namespace mpsfsi
