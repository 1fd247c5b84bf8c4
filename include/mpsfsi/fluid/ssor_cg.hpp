// SPDX-License-Identifier: BSD-3-Clause
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>
#include <string>
#include <type_traits>
#include <vector>

#include "mpsfsi/core/abi.hpp"
#include "mpsfsi/core/detail/format.hpp"
#include "mpsfsi/core/error.hpp"
#include "mpsfsi/core/parallel.hpp"
#include "mpsfsi/fluid/detail/aggregate_deflation.hpp"
#include "mpsfsi/fluid/linear_solver.hpp"

namespace mpsfsi {
inline namespace MPSFSI_ABI {

namespace detail {

// sum of val[k] v[col[k]] over k in [begin, end) (one row: counted from begin in int), in four
// independent partial sums. In the SSOR sweeps each row waits for the rows before it; with one
// running sum the row's whole chain of dependent additions would sit on that path (measured 5x slower per iteration than Jacobi-CG in
// 3D, 58 terms a row). Forward (`Reversed` false) the terms are taken in increasing k, reversed
// in decreasing k, so the term of the nearest row, which is ready last, is added last.
template <bool Reversed>
inline double sparse_row_dot(const double* val, const int* col, const double* v, std::int64_t begin, std::int64_t end) {
  val += begin, col += begin;
  const int m = static_cast<int>(end - begin);
  double s0 = 0, s1 = 0, s2 = 0, s3 = 0;
  if constexpr (!Reversed) {
    int k = 0;
    for (; k + 4 <= m; k += 4) {
      s0 += val[k] * v[col[k]];
      s1 += val[k + 1] * v[col[k + 1]];
      s2 += val[k + 2] * v[col[k + 2]];
      s3 += val[k + 3] * v[col[k + 3]];
    }
    for (; k < m; ++k) s0 += val[k] * v[col[k]];
  } else {
    int k = m;
    for (; k - 4 >= 0; k -= 4) {
      s0 += val[k - 1] * v[col[k - 1]];
      s1 += val[k - 2] * v[col[k - 2]];
      s2 += val[k - 3] * v[col[k - 3]];
      s3 += val[k - 4] * v[col[k - 4]];
    }
    for (; k > 0; --k) s0 += val[k - 1] * v[col[k - 1]];
  }
  return (s1 + s2 + s3) + s0;
}

}  // namespace detail

// Conjugate gradient preconditioned by symmetric successive over-relaxation (SSOR), applied with
// Eisenstat's trick (Eisenstat 1981, SIAM J. Sci. Stat. Comput. 2:1; Saad, Iterative Methods for
// Sparse Linear Systems, 2nd ed., sec. 9.2.2), a linear-solver policy of FluidSolver.
//
// Split A = L + D + L^T (L strictly lower) and let L~ = D/omega + L. SSOR is M = L~ (D/omega)^-1
// L~^T, and CG with it is CG on A^ = L~^-1 A L~^-T with the preconditioner D/omega, for
// x^ = L~^T x. Since A = L~ + L~^T + K with K = (1 - 2/omega) D,
//   A^ v = t + L~^-1 (v + K t),  t = L~^-T v,
// one backward and one forward triangular sweep: together one pass over the matrix, the cost of
// the product in Jacobi-CG, for a quarter to a half of its iterations on the PPE (3.3-3.8x fewer
// in 2D, 1.9-2.3x in 3D; docs/performance.md).
//
// The sweeps are sequential. With T threads the rows are cut into T contiguous blocks and
// renumbered: first the interior of each block, block after block, then the separator, the
// rows coupled to an earlier block (in either direction, should the pattern not be symmetric),
// in their original order. In that order no two blocks' interiors couple, so a forward sweep
// runs the interiors in parallel, one thread each, and then the separator on one thread; a
// backward sweep runs the other way round. No coupling is dropped: this is SSOR in the new
// order, not a block-Jacobi approximation of it. Every other block's interior is numbered
// backwards (a "twisted" order: with two blocks both sweep towards the separator), so that rows
// next to the separator see it as their other neighbours in the sweep's direction. On the dam
// break's PPE two threads need 44 iterations against 43 on one; dropping the couplings between
// blocks had needed 59, and the separator numbered after a forward block 46. The separator,
// swept serially, is a thin layer on large 2D problems (261 of 4,974 rows there) but can be a
// quarter of a small 3D one (3,371 of 12,197 rows; docs/performance.md). The order depends on T,
// so the answer does (within the tolerance); with one thread it is the original order.
//
// Each solve first copies the matrix, renumbered, into two row-wise arrays, the part each sweep
// reads (L for the forward sweep, L^T for the backward one), so that both stream contiguous
// memory: reading every other half-row of the CSR arrays in place ran at half the speed of a
// whole product on a 3D PPE of 1e5 unknowns (139 MB). The copies cost one more matrix of
// memory; the CG vectors live in the new order, b and x are permuted in and out.
//
// Deflation (`deflation`, DeflatedSsorCg): CG on the deflated system P A x^ = P b
// (detail::AggregateDeflation: Z the indicator vectors of aggregates of rows, E = Z^T A Z,
// P = I - AZ E^-1 Z^T), SSOR-preconditioned in the same way. The operator of the transformed
// system is then L~^-1 P A L~^-T v = t + L~^-1 (v + K t - AZ E^-1 (AZ)^T t): the coarse
// correction enters the forward sweep's right-hand side. r0 is projected, and the answer is
// x = Z E^-1 Z^T b + P^T x^, whose true residual is the deflated one that CG tracks.
//
// Converged when |r| <= tolerance |b| for r = L~ r^ (r^ the recursively updated residual of the
// transformed system, so r is the recursively updated residual of A x = b, as in JacobiCg). r is
// formed only when |r^| predicts convergence, using the ratio |r|/|r^| of the last time it was.
// Requires each row's columns in increasing order (as PpeAssembler writes them; checked).
class SsorCg {
 public:
  double omega = 1.6;  // relaxation factor in (0, 2); 1.6-1.7 measured best on the 2D PPE
  // Deflate the piecewise constants over aggregates of rows (DeflatedSsorCg; see below).
  bool deflation = false;

  SolveReport solve(const PpeMatrix& a, const PpeVector& b, PpeVector& x, double tolerance, int max_iterations) {
    return solve_reusing(a, b, x, tolerance, max_iterations, false);
  }
  // solve() for the matrix of the last solve, unchanged (the pattern and the values: a fluid step
  // repeated from its start, FluidSolver::snapshot_restored). Reuses that solve's renumbered copies
  // and, with deflation, its coarse space: the same answer to the bit, without the set-up. Sets up
  // as solve() does if the last solve did not (or ran with other settings or threads).
  SolveReport solve_same_matrix(const PpeMatrix& a, const PpeVector& b, PpeVector& x, double tolerance,
                                int max_iterations) {
    return solve_reusing(a, b, x, tolerance, max_iterations, true);
  }

 private:
  // The solve; with `same_matrix`, the last solve's set-up if it has one for these settings.
  SolveReport solve_reusing(const PpeMatrix& a, const PpeVector& b, PpeVector& x, double tolerance,
                            int max_iterations, bool same_matrix) {
    if (!(omega > 0 && omega < 2)) detail::throw_invalid("SsorCg", "omega must lie in (0, 2), got " + detail::format_number(omega));
    if (!same_matrix) set_up_ = false;
    const auto n = static_cast<std::int64_t>(a.rows());
    if (x.size() != a.rows()) x = PpeVector::Zero(a.rows());
    const double bb = b.squaredNorm();
    if (n == 0 || bb == 0) {
      x.setZero();
      return SolveReport{true, 0, 0.0};
    }
    const int blocks = static_cast<int>(std::min<std::int64_t>(parallel::max_threads(), n));
    if (!(set_up_ && rows_ == n && set_up_blocks_ == blocks && set_up_omega_ == omega &&
          set_up_deflation_ == deflation)) {
      set_up_ = false;
      if (!split(a, blocks)) return SolveReport{false, 0, 1.0};
      deflating_ = deflation && deflation_.build(a, row_at_.data());
      set_up_ = true;
      set_up_blocks_ = blocks;
      set_up_omega_ = omega;
      set_up_deflation_ = deflation;
    }
    const bool deflate = deflating_;
    // Work vectors in one block, offset from each other within a 4 KiB page (see JacobiCg); all
    // but x0 in the sweeps' order.
    const std::size_t stride = (static_cast<std::size_t>(n) + 511) / 512 * 512 + 24;
    work_.resize(8 * stride + 8);
    double* const xh = work_.data();  // x^
    double* const r = xh + stride;    // r^
    double* const p = r + stride;
    double* const t = p + stride;  // L~^-T p
    double* const y = t + stride;  // L~^-1 (p + K t)
    double* const inv_dw = y + stride;
    double* const xs = inv_dw + stride;    // x in the sweeps' order
    double* const w = xs + stride;         // the coarse correction AZ E^-1 (AZ)^T t
    const double* const dw = dw_.data();  // D/omega
    const int* const outer = a.outerIndexPtr();
    const int* const col = a.innerIndexPtr();
    const double* const val = a.valuePtr();
    const std::int64_t* const lo = lower_first_.data();  // row k: L in [lo[k], lo[k+1])
    const int* const lcol = lower_col_.data();
    const double* const lval = lower_val_.data();
    const std::int64_t* const up = upper_first_.data();  // row k: L^T in [up[k], up[k+1])
    const int* const ucol = upper_col_.data();
    const double* const uval = upper_val_.data();
    const int* const position = position_.data();
    const double k_factor = omega - 2;  // K = (1 - 2/omega) D = (omega - 2) D/omega

    // r0 = b - A x0 (into y) and x0, in the sweeps' order.
    double rr = 0;
    MPSFSI_OMP(parallel for schedule(static) reduction(+ : rr))
    for (std::int64_t i = 0; i < n; ++i) {
      const int k = position[i];
      y[k] = b[i] - detail::sparse_row_dot<false>(val, col, x.data(), outer[i], outer[i + 1]);
      rr += y[k] * y[k];
      xs[k] = x[i];
    }
    const double threshold = tolerance * tolerance * bb;
    if (rr <= threshold) return SolveReport{true, 0, std::sqrt(rr / bb)};
    if (deflate) {  // r0 = P (b - A x0)
      deflation_.project(y);
      rr = 0;
      MPSFSI_OMP(parallel for schedule(static) reduction(+ : rr))
      for (std::int64_t k = 0; k < n; ++k) rr += y[k] * y[k];
    }
    // x^ = L~^T x0.
    MPSFSI_OMP(parallel for schedule(static))
    for (std::int64_t k = 0; k < n; ++k) {
      inv_dw[k] = 1 / dw[k];
      xh[k] = dw[k] * xs[k] + detail::sparse_row_dot<false>(uval, ucol, xs, up[k], up[k + 1]);
      p[k] = 0;
      w[k] = 0;
    }
    // r^ = L~^-1 r0, z = (D/omega) r^.
    double rz = 0, rrh = 0;
    forward_sweep(rz, rrh, [&](std::int64_t k, double& rz_sum, double& rrh_sum) {
      r[k] = (y[k] - detail::sparse_row_dot<false>(lval, lcol, r, lo[k], lo[k + 1])) * inv_dw[k];
      rz_sum += r[k] * dw[k] * r[k];
      rrh_sum += r[k] * r[k];
    });
    double ratio = rr / rrh;  // |r|^2 / |r^|^2 when last formed
    // |L~ r^|^2, the true residual's norm
    auto residual_norm2 = [&] {
      double sum = 0;
      MPSFSI_OMP(parallel for schedule(static) reduction(+ : sum))
      for (std::int64_t k = 0; k < n; ++k) {
        const double s = dw[k] * r[k] + detail::sparse_row_dot<false>(lval, lcol, r, lo[k], lo[k + 1]);
        sum += s * s;
      }
      return sum;
    };
    double beta = 0;
    int it = 0;
    bool converged = rr <= threshold;  // with deflation: b - A x0 was in the range of AZ
    while (!converged && it < max_iterations) {
      ++it;
      // p = z + beta p and t = L~^-T p, backward.
      backward_sweep([&](std::int64_t k) {
        const double pk = dw[k] * r[k] + beta * p[k];
        p[k] = pk;
        t[k] = (pk - detail::sparse_row_dot<true>(uval, ucol, t, up[k], up[k + 1])) * inv_dw[k];
      });
      // y = L~^-1 (p + K t - w), w = AZ E^-1 (AZ)^T t (zero without deflation), forward; q = t + y
      // is A^ p, deflated: L~^-1 P A L~^-T p.
      // Two instances, so the plain solver does not stream the zeros of w.
      double pq = 0, unused = 0;
      auto forward_with = [&](auto coarse) {
        forward_sweep(pq, unused, [&](std::int64_t k, double& pq_sum, double&) {
          double s = p[k] + k_factor * dw[k] * t[k];
          if constexpr (decltype(coarse)::value) s -= w[k];
          y[k] = (s - detail::sparse_row_dot<false>(lval, lcol, y, lo[k], lo[k + 1])) * inv_dw[k];
          pq_sum += p[k] * (t[k] + y[k]);
        });
      };
      if (deflate) {
        deflation_.coarse_correction(t, w);
        forward_with(std::true_type{});
      } else {
        forward_with(std::false_type{});
      }
      if (!(pq > 0)) break;  // the matrix is not positive definite along p
      const double alpha = rz / pq;
      double rz_new = 0;
      rrh = 0;
      MPSFSI_OMP(parallel for schedule(static) reduction(+ : rz_new, rrh))
      for (std::int64_t k = 0; k < n; ++k) {
        xh[k] += alpha * p[k];
        r[k] -= alpha * (t[k] + y[k]);
        rz_new += dw[k] * r[k] * r[k];
        rrh += r[k] * r[k];
      }
      beta = rz_new / rz;
      rz = rz_new;
      if (rrh * ratio <= threshold) {  // predicted converged: form r = L~ r^
        rr = residual_norm2();
        ratio = rr / rrh;
        if (rr <= threshold) {
          converged = true;
          break;
        }
      }
    }
    // x = L~^-T x^, backward, and back into the original order.
    backward_sweep([&](std::int64_t k) {
      xs[k] = (xh[k] - detail::sparse_row_dot<true>(uval, ucol, xs, up[k], up[k + 1])) * inv_dw[k];
    });
    if (deflate) {  // x = Z E^-1 Z^T b + P^T x^, b in the sweeps' order (into y)
      MPSFSI_OMP(parallel for schedule(static))
      for (std::int64_t k = 0; k < n; ++k) y[k] = b[row_at_[static_cast<std::size_t>(k)]];
      deflation_.finish(y, xs);
    }
    MPSFSI_OMP(parallel for schedule(static))
    for (std::int64_t i = 0; i < n; ++i) x[i] = xs[position[i]];
    if (!converged) rr = residual_norm2();  // where the iteration stopped
    return SolveReport{converged, it, std::sqrt(rr / bb)};
  }

  // row(k, sum1, sum2) for k = 0, 1, ..., n - 1 in dependency order: the blocks' interiors in
  // parallel, then the separator; the partial sums are added into sum1 and sum2.
  template <class Row>
  void forward_sweep(double& sum1, double& sum2, Row row) const {
    const int blocks = static_cast<int>(interior_first_.size()) - 1;
    const std::int64_t* const first = interior_first_.data();
    double s1 = 0, s2 = 0;
    MPSFSI_OMP(parallel for schedule(static, 1) reduction(+ : s1, s2))
    for (int blk = 0; blk < blocks; ++blk)
      for (std::int64_t k = first[blk]; k < first[blk + 1]; ++k) row(k, s1, s2);
    for (std::int64_t k = first[blocks]; k < rows_; ++k) row(k, s1, s2);
    sum1 += s1;
    sum2 += s2;
  }
  // row(k) for k = n - 1, ..., 0 in dependency order: the separator, then the blocks' interiors
  // in parallel.
  template <class Row>
  void backward_sweep(Row row) const {
    const int blocks = static_cast<int>(interior_first_.size()) - 1;
    const std::int64_t* const first = interior_first_.data();
    for (std::int64_t k = rows_ - 1; k >= first[blocks]; --k) row(k);
    MPSFSI_OMP(parallel for schedule(static, 1))
    for (int blk = 0; blk < blocks; ++blk)
      for (std::int64_t k = first[blk + 1] - 1; k >= first[blk]; --k) row(k);
  }

  // Cuts the rows into `blocks` contiguous blocks, numbers them in the sweeps' order (the
  // blocks' interiors, then the separator; see above) and copies each row's lower part (columns
  // earlier in that order) into lower_*, its upper part into upper_*, renumbered, and D/omega
  // into dw_, all in that order. False if a diagonal entry is missing or not positive.
  bool split(const PpeMatrix& a, int blocks) {
    rows_ = static_cast<std::int64_t>(a.rows());
    const std::int64_t n = rows_;
    const auto rows = static_cast<std::size_t>(n);
    const int* const outer = a.outerIndexPtr();
    const int* const col = a.innerIndexPtr();
    const double* const val = a.valuePtr();
    auto block_begin = [&](int blk) { return n * blk / blocks; };
    // The separator: rows with a column in an earlier block, and rows that a row of an earlier
    // block has a column in (the same rows if the pattern is symmetric).
    row_class_.assign(rows, interior);
    bool sorted = true;
    MPSFSI_OMP(parallel for schedule(static, 1) reduction(&& : sorted))
    for (int blk = 0; blk < blocks; ++blk)
      for (std::int64_t i = block_begin(blk); i < block_begin(blk + 1); ++i) {
        const int* const c0 = col + outer[i];
        const int* const c1 = col + outer[i + 1];
        sorted = sorted && std::adjacent_find(c0, c1, std::greater_equal<int>()) == c1;
        if (c0 != c1 && *c0 < block_begin(blk)) row_class_[static_cast<std::size_t>(i)] = separator;
      }
    if (!sorted) detail::throw_invalid("SsorCg", "each matrix row must list its columns in increasing order");
    for (int blk = 0; blk + 1 < blocks; ++blk) {
      const std::int64_t end = block_begin(blk + 1);
      for (std::int64_t i = block_begin(blk); i < end; ++i)
        for (std::int64_t k = outer[i + 1] - 1; k >= outer[i] && col[k] >= end; --k)
          row_class_[static_cast<std::size_t>(col[k])] = separator;
    }
    // Positions: block by block its interior rows (in row order, or backwards in odd blocks),
    // then the separator rows in row order.
    interior_first_.assign(static_cast<std::size_t>(blocks) + 1, 0);
    for (int blk = 0; blk < blocks; ++blk) {
      std::int64_t count = 0;
      for (std::int64_t i = block_begin(blk); i < block_begin(blk + 1); ++i) count += row_class_[static_cast<std::size_t>(i)] != separator;
      interior_first_[static_cast<std::size_t>(blk) + 1] = interior_first_[static_cast<std::size_t>(blk)] + count;
    }
    position_.resize(rows);
    row_at_.resize(rows);
    std::int64_t next_separator = interior_first_[static_cast<std::size_t>(blocks)];
    for (int blk = 0; blk < blocks; ++blk) {
      const bool reversed = blk % 2 == 1;
      std::int64_t next_interior = interior_first_[static_cast<std::size_t>(blk) + reversed] - reversed;
      for (std::int64_t i = block_begin(blk); i < block_begin(blk + 1); ++i) {
        auto& kind = row_class_[static_cast<std::size_t>(i)];
        std::int64_t k = 0;
        if (kind == separator) {
          k = next_separator++;
        } else if (reversed) {
          kind = reversed_interior;
          k = next_interior--;
        } else {
          k = next_interior++;
        }
        position_[static_cast<std::size_t>(i)] = static_cast<int>(k);
        row_at_[static_cast<std::size_t>(k)] = static_cast<int>(i);
      }
    }
    // A plain row: an interior row with no separator between its first and last column (so all
    // its columns are interior rows of its block, numbered in the same direction). Its lower
    // and upper parts are the stretches either side of the diagonal, found by bisection; other
    // rows (the separator and rows next to it) are classified entry by entry.
    separators_before_.resize(rows + 1);
    separators_before_[0] = 0;
    for (std::size_t i = 0; i < rows; ++i) separators_before_[i + 1] = separators_before_[i] + (row_class_[i] == separator);
    auto plain = [&](std::int64_t i) {
      const int* const c0 = col + outer[i];
      const int* const c1 = col + outer[i + 1];
      return row_class_[static_cast<std::size_t>(i)] != separator && c0 != c1 &&
             separators_before_[static_cast<std::size_t>(c1[-1]) + 1] == separators_before_[static_cast<std::size_t>(*c0)];
    };
    // Pass 1: per row, the sizes of its lower and upper parts, and D/omega.
    lower_first_.resize(rows + 1);
    upper_first_.resize(rows + 1);
    dw_.resize(rows);
    const int* const position = position_.data();
    bool ok = true;
    MPSFSI_OMP(parallel for schedule(static) reduction(&& : ok))
    for (std::int64_t k = 0; k < n; ++k) {
      const std::int64_t i = row_at_[static_cast<std::size_t>(k)];
      std::int64_t lower = 0, upper = 0;
      double diagonal = 0;
      if (plain(i)) {
        const int* const c0 = col + outer[i];
        const int* const c1 = col + outer[i + 1];
        const int* const d = std::lower_bound(c0, c1, static_cast<int>(i));
        const bool has_diag = d != c1 && *d == i;
        diagonal = has_diag ? val[d - col] : 0;
        const std::int64_t before = d - c0, after = c1 - d - has_diag;
        const bool reversed = row_class_[static_cast<std::size_t>(i)] == reversed_interior;
        lower = reversed ? after : before;
        upper = reversed ? before : after;
      } else {
        for (std::int64_t e = outer[i]; e < outer[i + 1]; ++e) {
          const int ke = position[col[e]];
          lower += ke < k;
          upper += ke > k;
          if (ke == k) diagonal = val[e];
        }
      }
      ok = ok && diagonal > 0;
      lower_first_[static_cast<std::size_t>(k) + 1] = lower;
      upper_first_[static_cast<std::size_t>(k) + 1] = upper;
      dw_[static_cast<std::size_t>(k)] = diagonal > 0 ? diagonal / omega : 1.0;
    }
    if (!ok) return false;
    lower_first_[0] = upper_first_[0] = 0;
    for (std::size_t k = 0; k < rows; ++k) {  // counts to offsets
      lower_first_[k + 1] += lower_first_[k];
      upper_first_[k + 1] += upper_first_[k];
    }
    lower_col_.resize(static_cast<std::size_t>(lower_first_[rows]));
    lower_val_.resize(lower_col_.size());
    upper_col_.resize(static_cast<std::size_t>(upper_first_[rows]));
    upper_val_.resize(upper_col_.size());
    // Pass 2: copy, renumbered, each part in increasing position as far as the row's order
    // allows (backwards in a reversed block); the same static schedule as the sweeps' loops over
    // k, so each thread first touches the rows it reads most.
    MPSFSI_OMP(parallel for schedule(static))
    for (std::int64_t k = 0; k < n; ++k) {
      const std::int64_t i = row_at_[static_cast<std::size_t>(k)];
      int* lc = lower_col_.data() + lower_first_[static_cast<std::size_t>(k)];
      double* lv = lower_val_.data() + lower_first_[static_cast<std::size_t>(k)];
      int* uc = upper_col_.data() + upper_first_[static_cast<std::size_t>(k)];
      double* uv = upper_val_.data() + upper_first_[static_cast<std::size_t>(k)];
      const bool reversed = row_class_[static_cast<std::size_t>(i)] == reversed_interior;
      if (plain(i)) {
        const std::int64_t b = outer[i], e = outer[i + 1];
        const std::int64_t d = std::lower_bound(col + b, col + e, static_cast<int>(i)) - col;  // the diagonal
        auto copy = [&](std::int64_t from, std::int64_t to, int* cols, double* vals) {  // [from, to), renumbered
          if (reversed)
            for (std::int64_t m = to - 1; m >= from; --m) *cols++ = position[col[m]], *vals++ = val[m];
          else
            for (std::int64_t m = from; m < to; ++m) *cols++ = position[col[m]], *vals++ = val[m];
        };
        copy(b, d, reversed ? uc : lc, reversed ? uv : lv);
        copy(d + 1, e, reversed ? lc : uc, reversed ? lv : uv);
        continue;
      }
      for (std::int64_t m = outer[i]; m < outer[i + 1]; ++m) {
        const std::int64_t e = reversed ? outer[i] + outer[i + 1] - 1 - m : m;
        const int ke = position[col[e]];
        if (ke < k) {
          *lc++ = ke;
          *lv++ = val[e];
        } else if (ke > k) {
          *uc++ = ke;
          *uv++ = val[e];
        }
      }
    }
    return true;
  }

  std::vector<double> work_;
  std::int64_t rows_ = 0;
  // The set-up (split, the coarse space) of the last solve, for solve_same_matrix.
  bool set_up_ = false, set_up_deflation_ = false, deflating_ = false;
  int set_up_blocks_ = 0;
  double set_up_omega_ = 0;
  enum RowClass : std::uint8_t { interior, reversed_interior, separator };
  std::vector<RowClass> row_class_;
  std::vector<std::int64_t> interior_first_;  // block b's interior: positions [first[b], first[b+1]); then the separator
  std::vector<int> position_, row_at_;         // row -> position in the sweeps' order, and back
  std::vector<int> separators_before_;         // separator rows among rows [0, i)
  std::vector<std::int64_t> lower_first_, upper_first_;  // row offsets into the copies
  std::vector<int> lower_col_, upper_col_;
  std::vector<double> lower_val_, upper_val_, dw_;
  detail::AggregateDeflation deflation_;
};

// SSOR-CG deflated by aggregates: on the 2D dam-break PPE 18 iterations instead of 44 (the step
// about as fast), on a 2D PPE of 1e5 unknowns 25 instead of 208 (3.0 times faster on one thread,
// 1.7 on two); on a 3D block slower, the coarse space costing more than the iterations save, but
// on deep water near rest, under the 3D floating strip, 13 iterations instead of 76 and the solve
// 2.4 times faster (docs/performance.md).
struct DeflatedSsorCg : SsorCg {
  DeflatedSsorCg() { deflation = true; }
};

}  // namespace MPSFSI_ABI
}  // namespace mpsfsi
