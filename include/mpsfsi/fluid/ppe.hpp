// SPDX-License-Identifier: BSD-3-Clause
#pragma once

#include <algorithm>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "mpsfsi/core/abi.hpp"
#include "mpsfsi/core/neighbor_list.hpp"
#include "mpsfsi/core/parallel.hpp"
#include "mpsfsi/core/particle_set.hpp"
#include "mpsfsi/core/types.hpp"
#include "mpsfsi/fluid/linear_solver.hpp"
#include "mpsfsi/kernels/detail/pair.hpp"
#include "mpsfsi/kernels/lattice_constants.hpp"

namespace mpsfsi {
inline namespace MPSFSI_ABI {

namespace detail {

// Work space of sort_row_by_column for one thread, sized once for the longest row.
struct RowSortBuffer {
  std::vector<int> cols, run_starts;
  std::vector<double> vals;
  void reserve_row(std::size_t length) {
    if (cols.size() < length) {
      cols.resize(length);
      vals.resize(length);
      run_starts.resize(length + 1);
    }
  }
};

// Sorts one CSR row (cols, vals: m entries) by column: a natural merge sort, or an insertion
// sort for short rows. A row comes from a neighbour-list row, which lists the neighbours cell by
// cell, so it is made of ascending runs; merging them pairwise moves each entry log2(runs)
// times, where an insertion sort moves it past every earlier entry with a larger column (on
// 120-entry 3D rows the assembly then takes 1.4 times as long; docs/performance.md).
inline void sort_row_by_column(int* cols, double* vals, int m, RowSortBuffer& buffer) {
  if (m < 64) {  // 2D rows (about 30 entries): the insertion sort measured faster there
    for (int p = 1; p < m; ++p) {
      const int col = cols[p];
      const double val = vals[p];
      int q = p - 1;
      for (; q >= 0 && cols[q] > col; --q) {
        cols[q + 1] = cols[q];
        vals[q + 1] = vals[q];
      }
      cols[q + 1] = col;
      vals[q + 1] = val;
    }
    return;
  }
  int* const starts = buffer.run_starts.data();
  int runs = 0;
  starts[runs++] = 0;
  for (int p = 1; p < m; ++p)
    if (cols[p] < cols[p - 1]) starts[runs++] = p;
  if (runs == 1) return;
  starts[runs] = m;
  int* from_cols = cols;
  double* from_vals = vals;
  int* to_cols = buffer.cols.data();
  double* to_vals = buffer.vals.data();
  while (runs > 1) {
    int merged = 0;
    for (int k = 0; k < runs; k += 2) {
      const int begin = starts[k], middle = starts[std::min(k + 1, runs)], end = starts[std::min(k + 2, runs)];
      int a = begin, b = middle, out = begin;
      while (a < middle && b < end) {
        const bool take_b = from_cols[b] < from_cols[a];
        const int src = take_b ? b++ : a++;
        to_cols[out] = from_cols[src];
        to_vals[out++] = from_vals[src];
      }
      for (; a < middle; ++a, ++out) to_cols[out] = from_cols[a], to_vals[out] = from_vals[a];
      for (; b < end; ++b, ++out) to_cols[out] = from_cols[b], to_vals[out] = from_vals[b];
      starts[merged++] = begin;
    }
    starts[merged] = m;
    runs = merged;
    std::swap(from_cols, to_cols);
    std::swap(from_vals, to_vals);
  }
  if (from_cols != cols) {
    std::copy_n(from_cols, m, cols);
    std::copy_n(from_vals, m, vals);
  }
}

}  // namespace detail

// The pressure Poisson equation, eq 11, discretised with the MPS Laplacian:
//   (2d/(lambda n0)) sum_j w_ij (P_j - P_i) = s_i,
// negated into the symmetric positive definite system
//   A_ii = c sum_j w_ij,  A_ij = -c w_ij,  b_i = -s_i,   c = 2d/(lambda n0),
// over the unknowns: fluid and wall particles not at the free surface. Neighbours at the free
// surface (P = 0, Dirichlet) add to the diagonal only; dummy particles are not unknowns and
// are left out, unless `ghost_gradient` is given (WallCondition::neumann): a dummy neighbour j of
// row i then stands for the ghost pressure P_i + G_i . (x_j - x_i), which moves its term
// c w_ij G_i . r_ij to the right-hand side, and the matrix stays as it is.
//
// Enclosed regions: a connected set of unknowns none of which has a Dirichlet neighbour (free
// surface, or a solid-kind particle) makes a pure Neumann block: singular, its pressure level
// undetermined, and CG diverges on it. assemble() finds them (a flood fill over the matrix from
// the rows that have a Dirichlet neighbour) and reports them in enclosed(). If they hold wall
// particles only (the closed faces of a crack, a wall block inside dummies) or if called with
// leave_out_enclosed, it takes them out of the system (P = 0 there) and assembles again; an
// enclosed region with fluid in it is otherwise left for the caller to report
// (enclosed_fluid()).
// Assembled straight into CSR: one counting pass, a prefix sum, one filling pass, OpenMP over
// rows, each row sorted by column (sort_row_by_column). The arrays keep their capacity from one
// step to the next.
template <class Weight, int Dim, class Scalar>
class PpeAssembler {
 public:
  // Unknown number of particle i, or -1 if it is not an unknown.
  const std::vector<Index>& row_of() const { return row_of_; }
  const std::vector<Index>& particle_of_row() const { return particle_of_row_; }
  std::size_t num_unknowns() const { return particle_of_row_.size(); }

  void assemble(const VecArray<Dim, Scalar>& x, const std::vector<ParticleKind>& kinds,
                const std::vector<std::uint8_t>& surface, const BasicNeighborList<Scalar>& list,
                const MpsConstants<Scalar>& lap, const std::vector<Scalar>& source, PpeMatrix& a, PpeVector& b,
                bool leave_out_enclosed = false, const VecArray<Dim, Scalar>* ghost_gradient = nullptr) {
    left_out_.clear();
    ghost_gradient_ = ghost_gradient;
    assemble_once(x, kinds, surface, list, lap, source, a, b);
    find_enclosed(a);
    enclosed_fluid_ = static_cast<std::size_t>(std::count_if(enclosed_.begin(), enclosed_.end(), [&](Index i) {
      return kinds[static_cast<std::size_t>(i)] == ParticleKind::fluid;
    }));
    if (enclosed_.empty() || (enclosed_fluid_ > 0 && !leave_out_enclosed)) return;
    left_out_.assign(x.size(), 0);
    for (const Index i : enclosed_) left_out_[static_cast<std::size_t>(i)] = 1;
    assemble_once(x, kinds, surface, list, lap, source, a, b);
  }

  // The right-hand side alone, for the rows and matrix of the last assemble(), built from the same
  // positions, kinds and list: b_i = -s_i plus, with `ghost_gradient`, the ghost terms of row i's
  // dummy neighbours, summed as assemble() sums them (the same b to the bit). For a step repeated
  // from its start, whose matrix is unchanged while the source is not.
  void update_right_hand_side(const VecArray<Dim, Scalar>& x, const std::vector<ParticleKind>& kinds,
                              const BasicNeighborList<Scalar>& list, const MpsConstants<Scalar>& lap,
                              const std::vector<Scalar>& source, PpeVector& b,
                              const VecArray<Dim, Scalar>* ghost_gradient = nullptr) {
    detail::require_list_rows(list, x.size(), "PpeAssembler::update_right_hand_side");
    if (row_of_.size() != x.size())
      detail::throw_invalid("PpeAssembler::update_right_hand_side",
                            "called for " + std::to_string(x.size()) + " particles after an assemble() for " +
                                std::to_string(row_of_.size()));
    const auto rows = static_cast<std::int64_t>(particle_of_row_.size());
    b.resize(rows);
    const Scalar c = Scalar(2 * Dim) / (lap.lambda * lap.n0);
    MPSFSI_OMP(parallel for schedule(static))
    for (std::int64_t r = 0; r < rows; ++r) {
      const auto i = static_cast<std::size_t>(particle_of_row_[static_cast<std::size_t>(r)]);
      Scalar ghost = 0;
      if (ghost_gradient)
        for (Offset k = list.begin(i); k < list.end(i); ++k) {
          const auto j = static_cast<std::size_t>(list.indices[k]);
          if (kinds[j] != ParticleKind::dummy) continue;
          const Vec<Dim, Scalar> rij = x[j] - x[i];
          const Scalar w = Weight::value(detail::pair_distance(list, k, rij), lap.re);
          if (w > 0) ghost += c * w * (*ghost_gradient)[i].dot(rij);
        }
      b[r] = static_cast<double>(ghost - source[i]);
    }
  }

  // Particles of the last assemble() that lie in enclosed regions (see above), in row order.
  const std::vector<Index>& enclosed() const { return enclosed_; }
  // How many of them are fluid particles. If none, the region was left out in any case.
  std::size_t enclosed_fluid() const { return enclosed_fluid_; }

 private:
  void assemble_once(const VecArray<Dim, Scalar>& x, const std::vector<ParticleKind>& kinds,
                     const std::vector<std::uint8_t>& surface, const BasicNeighborList<Scalar>& list,
                     const MpsConstants<Scalar>& lap, const std::vector<Scalar>& source, PpeMatrix& a, PpeVector& b) {
    const std::size_t n = x.size();
    detail::require_list_rows(list, n, "PpeAssembler::assemble");
    row_of_.resize(n);
    particle_of_row_.clear();
    for (std::size_t i = 0; i < n; ++i) {
      const bool unknown = kinds[i] != ParticleKind::dummy && kinds[i] != ParticleKind::solid && !surface[i] &&
                           (left_out_.empty() || !left_out_[i]);
      row_of_[i] = unknown ? static_cast<Index>(particle_of_row_.size()) : Index(-1);
      if (unknown) particle_of_row_.push_back(static_cast<Index>(i));
    }
    const auto rows = static_cast<std::int64_t>(particle_of_row_.size());
    a.resize(rows, rows);
    b.resize(rows);
    anchored_.assign(static_cast<std::size_t>(rows), 0);
    int* outer = a.outerIndexPtr();

    // Pass 1: entries per row (the diagonal plus every neighbour that is an unknown).
    outer[0] = 0;
    MPSFSI_OMP(parallel for schedule(static))
    for (std::int64_t r = 0; r < rows; ++r) {
      const auto i = static_cast<std::size_t>(particle_of_row_[static_cast<std::size_t>(r)]);
      int count = 1;
      for (Offset k = list.begin(i); k < list.end(i); ++k) {
        const auto j = static_cast<std::size_t>(list.indices[k]);
        if (row_of_[j] < 0) continue;
        const Vec<Dim, Scalar> rij = x[j] - x[i];
        if (Weight::value(detail::pair_distance(list, k, rij), lap.re) > 0) ++count;
      }
      outer[r + 1] = count;
    }
    int longest = 0;
    for (std::int64_t r = 0; r < rows; ++r) {
      longest = std::max(longest, outer[r + 1]);
      outer[r + 1] += outer[r];
    }
    sort_buffers_.resize(static_cast<std::size_t>(parallel::max_threads()));
    for (auto& buffer : sort_buffers_) buffer.reserve_row(static_cast<std::size_t>(longest));
    a.resizeNonZeros(outer[rows]);
    int* cols = a.innerIndexPtr();
    double* vals = a.valuePtr();

    // Pass 2: values; the row is then sorted by column.
    const Scalar c = Scalar(2 * Dim) / (lap.lambda * lap.n0);
    MPSFSI_OMP(parallel for schedule(static))
    for (std::int64_t r = 0; r < rows; ++r) {
      const auto i = static_cast<std::size_t>(particle_of_row_[static_cast<std::size_t>(r)]);
      int pos = outer[r];
      const int diag_pos = pos++;
      Scalar diag = 0, ghost = 0;
      for (Offset k = list.begin(i); k < list.end(i); ++k) {
        const auto j = static_cast<std::size_t>(list.indices[k]);
        if (kinds[j] == ParticleKind::dummy && !ghost_gradient_) continue;
        const Vec<Dim, Scalar> rij = x[j] - x[i];
        const Scalar w = Weight::value(detail::pair_distance(list, k, rij), lap.re);
        if (!(w > 0)) continue;
        if (kinds[j] == ParticleKind::dummy) {
          ghost += c * w * (*ghost_gradient_)[i].dot(rij);
          continue;
        }
        diag += c * w;
        if (row_of_[j] >= 0) {
          cols[pos] = row_of_[j];
          vals[pos] = static_cast<double>(-c * w);
          ++pos;
        } else {
          anchored_[static_cast<std::size_t>(r)] = 1;  // a Dirichlet neighbour
        }
      }
      cols[diag_pos] = static_cast<int>(r);
      vals[diag_pos] = static_cast<double>(diag);
      detail::sort_row_by_column(cols + outer[r], vals + outer[r], outer[r + 1] - outer[r],
                                 sort_buffers_[static_cast<std::size_t>(parallel::thread_id())]);
      b[r] = static_cast<double>(ghost - source[i]);
    }
  }

  // Flood fill from the anchored rows along the matrix pattern; rows not reached are enclosed.
  void find_enclosed(const PpeMatrix& a) {
    enclosed_.clear();
    const std::size_t rows = particle_of_row_.size();
    const int* outer = a.outerIndexPtr();
    const int* cols = a.innerIndexPtr();
    front_.clear();
    for (std::size_t r = 0; r < rows; ++r)
      if (anchored_[r]) front_.push_back(static_cast<int>(r));
    if (front_.size() == rows) return;
    for (std::size_t head = 0; head < front_.size(); ++head) {
      const int r = front_[head];
      for (int k = outer[r]; k < outer[r + 1]; ++k)
        if (!anchored_[static_cast<std::size_t>(cols[k])]) {
          anchored_[static_cast<std::size_t>(cols[k])] = 1;
          front_.push_back(cols[k]);
        }
    }
    for (std::size_t r = 0; r < rows; ++r)
      if (!anchored_[r]) enclosed_.push_back(particle_of_row_[r]);
  }

  const VecArray<Dim, Scalar>* ghost_gradient_ = nullptr;
  std::vector<Index> row_of_;
  std::vector<Index> particle_of_row_;
  std::vector<std::uint8_t> anchored_, left_out_;
  std::vector<int> front_;
  std::vector<detail::RowSortBuffer> sort_buffers_;  // one a thread
  std::vector<Index> enclosed_;
  std::size_t enclosed_fluid_ = 0;
};

}  // namespace MPSFSI_ABI
}  // namespace mpsfsi
