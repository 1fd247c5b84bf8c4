// SPDX-License-Identifier: BSD-3-Clause
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "mpsfsi/core/error.hpp"
#include "mpsfsi/core/parallel.hpp"
#include "mpsfsi/fluid/linear_solver.hpp"

namespace mpsfsi {

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
// the product in Jacobi-CG, for a third to a half of its iterations on the PPE (README).
//
// The sweeps are sequential, so with T threads the rows are cut into T contiguous blocks and L
// keeps only the couplings inside a block (block-Jacobi SSOR); the couplings between blocks, C,
// enter as A^ v = t + L~^-1 (v + K t + C t). Each thread sweeps its own block. The
// preconditioner, and so the iteration count, depends on the thread count; the answer does not,
// beyond the tolerance.
//
// Each solve first copies the matrix into two row-wise arrays, the part each sweep reads (C and
// the in-block L for the forward sweep, the in-block L^T for the backward one), so that both
// stream contiguous memory: reading every other half-row of the CSR arrays in place ran at half
// the speed of a whole product on a 3D PPE of 1e5 unknowns (139 MB). The copies cost one more
// matrix of memory.
//
// Converged when |r| <= tolerance |b| for r = L~ r^ (r^ the recursively updated residual of the
// transformed system, so r is the recursively updated residual of A x = b, as in JacobiCg). r is
// formed only when |r^| predicts convergence, using the ratio |r|/|r^| of the last time it was.
// Requires each row's columns in increasing order (as PpeAssembler writes them; checked).
class SsorCg {
 public:
  double omega = 1.6;  // relaxation factor in (0, 2); 1.6-1.7 measured best on the 2D PPE

  SolveReport solve(const PpeMatrix& a, const PpeVector& b, PpeVector& x, double tolerance, int max_iterations) {
    if (!(omega > 0 && omega < 2)) detail::throw_invalid("SsorCg", "omega must lie in (0, 2), got " + std::to_string(omega));
    const auto n = static_cast<std::int64_t>(a.rows());
    if (x.size() != a.rows()) x = PpeVector::Zero(a.rows());
    const double bb = b.squaredNorm();
    if (n == 0 || bb == 0) {
      x.setZero();
      return SolveReport{true, 0, 0.0};
    }
    const int blocks = static_cast<int>(std::min<std::int64_t>(parallel::max_threads(), n));
    if (!split(a, blocks)) return SolveReport{false, 0, 1.0};
    // Work vectors in one block, offset from each other within a 4 KiB page (see JacobiCg).
    const std::size_t stride = (static_cast<std::size_t>(n) + 511) / 512 * 512 + 24;
    work_.resize(6 * stride + 8);
    double* const xh = work_.data();  // x^
    double* const r = xh + stride;    // r^
    double* const p = r + stride;
    double* const t = p + stride;     // L~^-T p
    double* const y = t + stride;     // L~^-1 (p + K t + C t)
    double* const inv_dw = y + stride;
    const double* const dw = dw_.data();  // D/omega
    const int* const outer = a.outerIndexPtr();
    const int* const col = a.innerIndexPtr();
    const double* const val = a.valuePtr();
    const std::int64_t* const lo = lower_first_.data();  // row i: C in [lo[i], in[i]), L in [in[i], lo[i+1])
    const std::int64_t* const in = lower_inside_.data();
    const int* const lcol = lower_col_.data();
    const double* const lval = lower_val_.data();
    const std::int64_t* const up = upper_first_.data();  // row i: L^T in [up[i], up[i+1])
    const int* const ucol = upper_col_.data();
    const double* const uval = upper_val_.data();
    const std::int64_t* const first = first_row_.data();
    const double k_factor = omega - 2;  // K = (1 - 2/omega) D = (omega - 2) D/omega

    // r0 = b - A x0 (into y) and x^ = L~^T x0.
    double rr = 0;
    MPSFSI_OMP(parallel for schedule(static) reduction(+ : rr))
    for (std::int64_t i = 0; i < n; ++i) {
      inv_dw[i] = 1 / dw[i];
      y[i] = b[i] - detail::sparse_row_dot<false>(val, col, x.data(), outer[i], outer[i + 1]);
      rr += y[i] * y[i];
      xh[i] = dw[i] * x[i] + detail::sparse_row_dot<false>(uval, ucol, x.data(), up[i], up[i + 1]);
      p[i] = 0;
    }
    const double threshold = tolerance * tolerance * bb;
    if (rr <= threshold) return SolveReport{true, 0, std::sqrt(rr / bb)};
    // r^ = L~^-1 r0, z = (D/omega) r^.
    double rz = 0, rrh = 0;
    MPSFSI_OMP(parallel for schedule(static, 1) reduction(+ : rz, rrh))
    for (int blk = 0; blk < blocks; ++blk)
      for (std::int64_t i = first[blk]; i < first[blk + 1]; ++i) {
        r[i] = (y[i] - detail::sparse_row_dot<false>(lval, lcol, r, in[i], lo[i + 1])) * inv_dw[i];
        rz += r[i] * dw[i] * r[i];
        rrh += r[i] * r[i];
      }
    double ratio = rr / rrh;  // |r|^2 / |r^|^2 when last formed
    // |L~ r^|^2, the true residual's norm
    auto residual_norm2 = [&] {
      double sum = 0;
      MPSFSI_OMP(parallel for schedule(static) reduction(+ : sum))
      for (std::int64_t i = 0; i < n; ++i) {
        const double s = dw[i] * r[i] + detail::sparse_row_dot<false>(lval, lcol, r, in[i], lo[i + 1]);
        sum += s * s;
      }
      return sum;
    };
    double beta = 0;
    int it = 0;
    bool converged = false;
    while (it < max_iterations) {
      ++it;
      // p = z + beta p and t = L~^-T p, backward through each block.
      MPSFSI_OMP(parallel for schedule(static, 1))
      for (int blk = 0; blk < blocks; ++blk)
        for (std::int64_t i = first[blk + 1] - 1; i >= first[blk]; --i) {
          const double pi = dw[i] * r[i] + beta * p[i];
          p[i] = pi;
          t[i] = (pi - detail::sparse_row_dot<true>(uval, ucol, t, up[i], up[i + 1])) * inv_dw[i];
        }
      // y = L~^-1 (p + K t + C t), forward through each block; q = A^ p = t + y.
      double pq = 0;
      MPSFSI_OMP(parallel for schedule(static, 1) reduction(+ : pq))
      for (int blk = 0; blk < blocks; ++blk)
        for (std::int64_t i = first[blk]; i < first[blk + 1]; ++i) {
          double s = p[i] + k_factor * dw[i] * t[i];
          for (std::int64_t k = lo[i]; k < in[i]; ++k) s += lval[k] * t[lcol[k]];  // C t
          y[i] = (s - detail::sparse_row_dot<false>(lval, lcol, y, in[i], lo[i + 1])) * inv_dw[i];
          pq += p[i] * (t[i] + y[i]);
        }
      if (!(pq > 0)) break;  // the matrix is not positive definite along p
      const double alpha = rz / pq;
      double rz_new = 0;
      rrh = 0;
      MPSFSI_OMP(parallel for schedule(static) reduction(+ : rz_new, rrh))
      for (std::int64_t i = 0; i < n; ++i) {
        xh[i] += alpha * p[i];
        r[i] -= alpha * (t[i] + y[i]);
        rz_new += dw[i] * r[i] * r[i];
        rrh += r[i] * r[i];
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
    // x = L~^-T x^, backward through each block.
    MPSFSI_OMP(parallel for schedule(static, 1))
    for (int blk = 0; blk < blocks; ++blk)
      for (std::int64_t i = first[blk + 1] - 1; i >= first[blk]; --i)
        x[i] = (xh[i] - detail::sparse_row_dot<true>(uval, ucol, x.data(), up[i], up[i + 1])) * inv_dw[i];
    if (!converged) rr = residual_norm2();  // where the iteration stopped
    return SolveReport{converged, it, std::sqrt(rr / bb)};
  }

 private:
  // Row i of block [begin, end), its columns increasing: [c0, inside) and [beyond, c1) couple it
  // to other blocks (C), [inside, diag) is L, diag the diagonal (if present), (diag, beyond) L^T.
  struct RowParts {
    const int* inside;
    const int* diag;
    const int* beyond;
    RowParts(const int* c0, const int* c1, std::int64_t begin, std::int64_t i, std::int64_t end)
        : inside(std::lower_bound(c0, c1, static_cast<int>(begin))),
          diag(std::lower_bound(inside, c1, static_cast<int>(i))),
          beyond(std::lower_bound(diag, c1, static_cast<int>(end))) {}
  };

  // Cuts the rows into `blocks` contiguous blocks and copies, per row, the couplings to other
  // blocks and the in-block lower part into lower_*, the in-block upper part into upper_*, and
  // D/omega into dw_. False if a diagonal entry is missing or not positive.
  bool split(const PpeMatrix& a, int blocks) {
    const auto n = static_cast<std::int64_t>(a.rows());
    const auto rows = static_cast<std::size_t>(n);
    first_row_.resize(static_cast<std::size_t>(blocks) + 1);
    for (int blk = 0; blk <= blocks; ++blk) first_row_[static_cast<std::size_t>(blk)] = n * blk / blocks;
    lower_first_.resize(rows + 1);
    lower_inside_.resize(rows);
    upper_first_.resize(rows + 1);
    dw_.resize(rows);
    const int* const outer = a.outerIndexPtr();
    const int* const col = a.innerIndexPtr();
    const double* const val = a.valuePtr();
    // Pass 1: per row (its columns increasing), the sizes of its parts in C, L and L^T, and
    // D/omega. The row is [C before the block | L | diagonal | L^T | C after the block].
    bool ok = true, sorted = true;
    MPSFSI_OMP(parallel for schedule(static, 1) reduction(&& : ok, sorted))
    for (int blk = 0; blk < blocks; ++blk) {
      const std::int64_t begin = first_row_[static_cast<std::size_t>(blk)];
      const std::int64_t end = first_row_[static_cast<std::size_t>(blk) + 1];
      for (std::int64_t i = begin; i < end; ++i) {
        const auto row = static_cast<std::size_t>(i);
        const int* const c0 = col + outer[i];
        const int* const c1 = col + outer[i + 1];
        const bool row_sorted = std::adjacent_find(c0, c1, std::greater_equal<int>()) == c1;
        sorted = sorted && row_sorted;
        if (!row_sorted) continue;
        const RowParts parts(c0, c1, begin, i, end);
        const bool has_diag = parts.diag != c1 && *parts.diag == i && val[parts.diag - col] > 0;
        ok = ok && has_diag;
        const std::int64_t cross = (parts.inside - c0) + (c1 - parts.beyond);
        lower_first_[row + 1] = cross + (parts.diag - parts.inside);
        lower_inside_[row] = cross;
        upper_first_[row + 1] = has_diag ? parts.beyond - parts.diag - 1 : 0;
        dw_[row] = has_diag ? val[parts.diag - col] / omega : 1.0;
      }
    }
    if (!sorted) detail::throw_invalid("SsorCg", "each matrix row must list its columns in increasing order");
    if (!ok) return false;
    lower_first_[0] = upper_first_[0] = 0;
    for (std::size_t i = 0; i < rows; ++i) {  // counts to offsets
      lower_first_[i + 1] += lower_first_[i];
      lower_inside_[i] += lower_first_[i];
      upper_first_[i + 1] += upper_first_[i];
    }
    lower_col_.resize(static_cast<std::size_t>(lower_first_[rows]));
    lower_val_.resize(lower_col_.size());
    upper_col_.resize(static_cast<std::size_t>(upper_first_[rows]));
    upper_val_.resize(upper_col_.size());
    // Pass 2: copy the four stretches of each row (each block writes its own rows, so each
    // thread first touches its own part).
    MPSFSI_OMP(parallel for schedule(static, 1))
    for (int blk = 0; blk < blocks; ++blk) {
      const std::int64_t begin = first_row_[static_cast<std::size_t>(blk)];
      const std::int64_t end = first_row_[static_cast<std::size_t>(blk) + 1];
      for (std::int64_t i = begin; i < end; ++i) {
        const auto row = static_cast<std::size_t>(i);
        const int* const c0 = col + outer[i];
        const int* const c1 = col + outer[i + 1];
        const RowParts parts(c0, c1, begin, i, end);
        const double* const v0 = val + outer[i];
        auto copy = [&](const int* from, const int* to, std::vector<int>& cols, std::vector<double>& vals, std::int64_t at) {
          std::copy(from, to, cols.data() + at);
          std::copy(v0 + (from - c0), v0 + (to - c0), vals.data() + at);
          return at + (to - from);
        };
        std::int64_t at = copy(c0, parts.inside, lower_col_, lower_val_, lower_first_[row]);  // C, before the block
        at = copy(parts.beyond, c1, lower_col_, lower_val_, at);                              // C, after it
        copy(parts.inside, parts.diag, lower_col_, lower_val_, at);                           // L
        copy(parts.diag + 1, parts.beyond, upper_col_, upper_val_, upper_first_[row]);        // L^T
      }
    }
    return true;
  }

  std::vector<double> work_;
  std::vector<std::int64_t> first_row_;  // block b holds rows [first_row_[b], first_row_[b+1])
  std::vector<std::int64_t> lower_first_, lower_inside_, upper_first_;  // row offsets into the copies
  std::vector<int> lower_col_, upper_col_;
  std::vector<double> lower_val_, upper_val_, dw_;
};

}  // namespace mpsfsi
