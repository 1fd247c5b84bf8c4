// SPDX-License-Identifier: BSD-3-Clause
#pragma once

#include <algorithm>
#include <cstdint>
#include <utility>
#include <vector>

#include <Eigen/SparseCholesky>

#include "mpsfsi/core/abi.hpp"
#include "mpsfsi/core/parallel.hpp"
#include "mpsfsi/fluid/linear_solver.hpp"

namespace mpsfsi {
inline namespace MPSFSI_ABI {
namespace detail {

// The coarse space of a deflated CG (DPCG; Tang, Nabben, Vuik & Erlangga 2009, J. Sci. Comput.
// 39:340, the DEF1 variant): Z's columns are the indicator vectors of aggregates of rows, the
// coarse matrix is E = Z^T A Z, and the projection is P = I - A Z E^-1 Z^T. CG on P A x^ = P b
// does not see the smooth, slowly converging error components that Z spans; the answer is
// x = Z E^-1 Z^T b + P^T x^ (finish), and P b - P A x^ is its true residual.
//
// Aggregates are cut from the matrix graph alone, greedily in row order: an unaggregated row
// takes every unaggregated neighbour. The PPE's rows are particles and its neighbours those
// within the Laplacian's radius, so an aggregate is a patch of about a dozen particles (427
// aggregates of the 2D dam-break PPE's 4,991 rows); on that PPE SSOR-CG then needs 18 iterations
// instead of 44 (docs/performance.md).
//
// Z is kept with the rows in the caller's order (`row_at[k]`: the matrix row at position k):
// the thin matrix AZ (each row's entries summed per aggregate, about 5 a row in 2D) and the
// sparse LDL^T factors of E. The sums of (AZ)^T v follow the thread count (each thread sums its
// block of rows), so the answer does within round-off, as SsorCg's order does.
class AggregateDeflation {
 public:
  // Everything here is work space that build() fills anew (and Eigen's factorization object
  // cannot be copied or moved), so a copy starts empty.
  AggregateDeflation() = default;
  AggregateDeflation(const AggregateDeflation&) {}
  AggregateDeflation& operator=(const AggregateDeflation&) { return *this; }

  // Builds aggregates, AZ and E's factors for the n x n matrix a. False if E is not positive
  // definite (then a is not either).
  bool build(const PpeMatrix& a, const int* row_at) {
    const auto n = static_cast<std::int64_t>(a.rows());
    const int* const outer = a.outerIndexPtr();
    const int* const col = a.innerIndexPtr();
    const double* const val = a.valuePtr();
    // Greedy aggregation in the matrix's row order.
    aggregate_of_row_.assign(static_cast<std::size_t>(n), -1);
    int m = 0;
    for (std::int64_t i = 0; i < n; ++i) {
      if (aggregate_of_row_[static_cast<std::size_t>(i)] >= 0) continue;
      for (int e = outer[i]; e < outer[i + 1]; ++e)
        if (aggregate_of_row_[static_cast<std::size_t>(col[e])] < 0) aggregate_of_row_[static_cast<std::size_t>(col[e])] = m;
      aggregate_of_row_[static_cast<std::size_t>(i)] = m++;
    }
    m_ = m;
    // Positions by aggregate (a counting sort), and each position's aggregate.
    aggregate_.resize(static_cast<std::size_t>(n));
    member_first_.assign(static_cast<std::size_t>(m) + 1, 0);
    for (std::int64_t k = 0; k < n; ++k) {
      const int c = aggregate_of_row_[static_cast<std::size_t>(row_at[k])];
      aggregate_[static_cast<std::size_t>(k)] = c;
      ++member_first_[static_cast<std::size_t>(c) + 1];
    }
    for (int c = 0; c < m; ++c) member_first_[static_cast<std::size_t>(c) + 1] += member_first_[static_cast<std::size_t>(c)];
    members_.resize(static_cast<std::size_t>(n));
    next_.assign(member_first_.begin(), member_first_.end() - 1);
    for (std::int64_t k = 0; k < n; ++k) members_[static_cast<std::size_t>(next_[static_cast<std::size_t>(aggregate_[static_cast<std::size_t>(k)])]++)] = static_cast<int>(k);
    // AZ, row by row in the caller's order, stored where the matrix row's entries are:
    // [az_first[k], az_first[k] + az_count[k]). Without branches (whether an entry's aggregate
    // is new to the row is a coin toss): each entry adds to sum[c] and appends c to the row's
    // list, which moves on only if c was not yet marked; sum and mark are arrays over the
    // aggregates, one a thread, zero between rows.
    const int threads = parallel::max_threads();
    az_first_.resize(static_cast<std::size_t>(n));
    az_count_.resize(static_cast<std::size_t>(n));
    az_col_.resize(std::max(az_col_.size(), static_cast<std::size_t>(a.nonZeros())));
    az_val_.resize(az_col_.size());
    place_.assign(static_cast<std::size_t>(threads) * static_cast<std::size_t>(m), 0);
    sum_.assign(static_cast<std::size_t>(threads) * copies * static_cast<std::size_t>(m), 0.0);
    MPSFSI_OMP(parallel for schedule(static))
    for (std::int64_t k = 0; k < n; ++k) {
      const int i = row_at[k];
      int* const cols = az_col_.data() + outer[i];
      double* const vals = az_val_.data() + outer[i];
      const auto thread = static_cast<std::size_t>(parallel::thread_id());
      int* const mark = place_.data() + thread * static_cast<std::size_t>(m);
      double* const sum = sum_.data() + thread * copies * static_cast<std::size_t>(m);
      int count = 0;
      for (int e = outer[i]; e < outer[i + 1]; ++e) {
        const int c = aggregate_of_row_[static_cast<std::size_t>(col[e])];
        sum[c] += val[e];
        cols[count] = c;
        count += 1 - mark[c];
        mark[c] = 1;
      }
      for (int q = 0; q < count; ++q) {
        vals[q] = sum[cols[q]];
        sum[cols[q]] = 0.0;
        mark[cols[q]] = 0;
      }
      az_count_[static_cast<std::size_t>(k)] = count;
    }
    // Compacted (about a fifth of the matrix's entries), so that the products with AZ stream.
    std::int64_t total = 0;
    for (std::int64_t k = 0; k < n; ++k) {
      az_first_[static_cast<std::size_t>(k)] = total;
      total += az_count_[static_cast<std::size_t>(k)];
    }
    compact_col_.resize(static_cast<std::size_t>(total));
    compact_val_.resize(static_cast<std::size_t>(total));
    MPSFSI_OMP(parallel for schedule(static))
    for (std::int64_t k = 0; k < n; ++k) {
      const auto from = static_cast<std::size_t>(outer[row_at[k]]);
      const auto to = static_cast<std::size_t>(az_first_[static_cast<std::size_t>(k)]);
      std::copy_n(az_col_.data() + from, az_count_[static_cast<std::size_t>(k)], compact_col_.data() + to);
      std::copy_n(az_val_.data() + from, az_count_[static_cast<std::size_t>(k)], compact_val_.data() + to);
    }
    az_col_.swap(compact_col_);
    az_val_.swap(compact_val_);
    // E = Z^T (AZ), symmetric: column c sums the AZ rows of c's members (without branches, as
    // AZ); written straight into E's compressed columns, each sorted by row.
    coarse_.resize(m, m);
    coarse_.resizeNonZeros(0);
    coarse_.reserve(static_cast<Eigen::Index>(total));  // E has at most AZ's entries
    int* const mark = place_.data();
    double* const sum = sum_.data();
    Eigen::Index nonzeros = 0;
    for (int c = 0; c < m; ++c) {
      coarse_.outerIndexPtr()[c] = static_cast<int>(nonzeros);
      std::int64_t length = 0;
      for (std::int64_t s = member_first_[static_cast<std::size_t>(c)]; s < member_first_[static_cast<std::size_t>(c) + 1]; ++s)
        length += az_count_[static_cast<std::size_t>(members_[static_cast<std::size_t>(s)])];
      coarse_.data().resize(nonzeros + static_cast<Eigen::Index>(length));
      int* const rows = coarse_.innerIndexPtr() + nonzeros;
      double* const values = coarse_.valuePtr() + nonzeros;
      int count = 0;
      for (std::int64_t s = member_first_[static_cast<std::size_t>(c)]; s < member_first_[static_cast<std::size_t>(c) + 1]; ++s) {
        const auto k = static_cast<std::size_t>(members_[static_cast<std::size_t>(s)]);
        const int* const cols = az_col_.data() + az_first_[k];
        const double* const vals = az_val_.data() + az_first_[k];
        for (int q = 0; q < az_count_[k]; ++q) {
          sum[cols[q]] += vals[q];
          rows[count] = cols[q];
          count += 1 - mark[cols[q]];
          mark[cols[q]] = 1;
        }
      }
      for (int q = 1; q < count; ++q)  // insertion sort: about 9 entries
        for (int p = q; p > 0 && rows[p - 1] > rows[p]; --p) std::swap(rows[p - 1], rows[p]);
      for (int q = 0; q < count; ++q) {
        values[q] = sum[rows[q]];
        sum[rows[q]] = 0.0;
        mark[rows[q]] = 0;
      }
      nonzeros += count;
      coarse_.data().resize(nonzeros);
    }
    coarse_.outerIndexPtr()[m] = static_cast<int>(nonzeros);
    // The aggregates are numbered along the rows, so E is banded in its own order. A
    // fill-reducing order (AMD) costs more than it saves on small E (0.39 against 0.16 ms for
    // the 2D dam break's 427 aggregates) and is essential on large ones (a 2D PPE of 1e5
    // unknowns: 8,500 aggregates).
    use_amd_ = m > amd_above;
    const bool factored = use_amd_ ? factor(amd_) : factor(natural_);
    if (!factored) return false;
    rhs_.resize(m);
    e_.resize(m);
    return true;
  }

  int coarse_size() const { return m_; }

  // r -= AZ E^-1 Z^T r (r = P r), in the caller's order.
  void project(double* r) {
    const auto n = static_cast<std::int64_t>(aggregate_.size());
    rhs_.setZero();
    for (std::int64_t k = 0; k < n; ++k) rhs_[aggregate_[static_cast<std::size_t>(k)]] += r[k];
    solve_coarse();
    MPSFSI_OMP(parallel for schedule(static))
    for (std::int64_t k = 0; k < n; ++k) r[k] -= az_row_dot(k);
  }

  // e = E^-1 (AZ)^T v, then w = AZ e: the coarse correction AZ E^-1 (AZ)^T v of P A = A - AZ
  // E^-1 (AZ)^T, all in the caller's order.
  void coarse_correction(const double* v, double* w) {
    transposed_product(v);
    solve_coarse();
    const auto n = static_cast<std::int64_t>(aggregate_.size());
    MPSFSI_OMP(parallel for schedule(static))
    for (std::int64_t k = 0; k < n; ++k) w[k] = az_row_dot(k);
  }

  // x = x^ + Z E^-1 (Z^T b - (AZ)^T x^) = Z E^-1 Z^T b + P^T x^, in the caller's order (b too).
  void finish(const double* b, double* x) {
    const auto n = static_cast<std::int64_t>(aggregate_.size());
    transposed_product(x);
    rhs_ = -rhs_;
    for (std::int64_t k = 0; k < n; ++k) rhs_[aggregate_[static_cast<std::size_t>(k)]] += b[k];
    solve_coarse();
    MPSFSI_OMP(parallel for schedule(static))
    for (std::int64_t k = 0; k < n; ++k) x[k] += e_[aggregate_[static_cast<std::size_t>(k)]];
  }

 private:
  // Row k of AZ times e_.
  double az_row_dot(std::int64_t k) const {
    const std::int64_t first = az_first_[static_cast<std::size_t>(k)];
    const int* const cols = az_col_.data() + first;
    const double* const vals = az_val_.data() + first;
    double s = 0;
    for (int q = 0; q < az_count_[static_cast<std::size_t>(k)]; ++q) s += vals[q] * e_[cols[q]];
    return s;
  }
  // rhs_ = (AZ)^T v: each thread adds its block of rows into copies of its own (sum_), row k
  // into copy k mod 4, and the copies are then added in order. Consecutive rows add to the same
  // few aggregates; with one copy each addition waited for the last row's.
  void transposed_product(const double* v) {
    const auto n = static_cast<std::int64_t>(aggregate_.size());
    const auto m = static_cast<std::size_t>(m_);
    int team = 1;
    MPSFSI_OMP(parallel) {
      const int t = parallel::thread_id();
      const int nt = parallel::team_size();
      MPSFSI_OMP(single) team = nt;
      double* const mine = sum_.data() + static_cast<std::size_t>(t) * copies * m;
      std::fill(mine, mine + copies * m, 0.0);
      const std::int64_t lo = n * t / nt, hi = n * (t + 1) / nt;
      for (std::int64_t k = lo; k < hi; ++k) {
        const std::int64_t first = az_first_[static_cast<std::size_t>(k)];
        const int* const cols = az_col_.data() + first;
        const double* const vals = az_val_.data() + first;
        double* const copy = mine + static_cast<std::size_t>(k % copies) * m;
        for (int q = 0; q < az_count_[static_cast<std::size_t>(k)]; ++q) copy[cols[q]] += vals[q] * v[k];
      }
    }
    for (std::size_t c = 0; c < m; ++c) {
      double s = 0;
      for (std::size_t q = 0; q < static_cast<std::size_t>(team) * copies; ++q) s += sum_[q * m + c];
      rhs_[static_cast<Eigen::Index>(c)] = s;
    }
  }
  static constexpr std::size_t copies = 4;

  template <class Factors>
  bool factor(Factors& factors) {
    factors.compute(coarse_);
    if (factors.info() != Eigen::Success) return false;
    for (int c = 0; c < m_; ++c)
      if (!(factors.vectorD()[c] > 0)) return false;
    return true;
  }
  // e_ = E^-1 rhs_.
  void solve_coarse() {
    if (use_amd_)
      e_ = amd_.solve(rhs_);
    else
      e_ = natural_.solve(rhs_);
  }

  int m_ = 0;
  std::vector<int> aggregate_of_row_;  // by matrix row
  std::vector<int> aggregate_;         // by position in the caller's order
  std::vector<std::int64_t> member_first_, next_, az_first_;
  std::vector<int> members_, az_count_, az_col_, place_, compact_col_;
  std::vector<double> az_val_, sum_, compact_val_;
  Eigen::SparseMatrix<double> coarse_;
  static constexpr int amd_above = 1000;
  bool use_amd_ = false;
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>, Eigen::Lower, Eigen::NaturalOrdering<int>> natural_;
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>, Eigen::Lower, Eigen::AMDOrdering<int>> amd_;
  Eigen::VectorXd rhs_, e_;
};

}  // namespace detail
}  // namespace MPSFSI_ABI
}  // namespace mpsfsi
