// SPDX-License-Identifier: BSD-3-Clause
#pragma once

#include <algorithm>
#include <cstdint>
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
// Assembled in one pass over the pairs into scratch rows sized by the neighbour list, each row
// sorted by column, then packed into CSR; OpenMP over rows. The arrays keep their capacity from
// one step to the next.
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
    // Row r (particle i) has at most 1 + (its neighbours) entries: pass 1 writes them, diagonal
    // first, into the scratch rows at list.begin(i) + r, which do not overlap.
    scratch_cols_.resize(list.indices.size() + static_cast<std::size_t>(rows));
    scratch_vals_.resize(scratch_cols_.size());
    int* const outer = a.outerIndexPtr();

    // Pass 1, over the pairs: values, and each row's count into outer[r + 1]; the row is then
    // insertion-sorted by column (about 30 entries in 2D, 120 in 3D).
    const Scalar c = Scalar(2 * Dim) / (lap.lambda * lap.n0);
    MPSFSI_OMP(parallel for schedule(static))
    for (std::int64_t r = 0; r < rows; ++r) {
      const auto i = static_cast<std::size_t>(particle_of_row_[static_cast<std::size_t>(r)]);
      const Offset first = list.begin(i) + static_cast<Offset>(r);
      int* const cols = scratch_cols_.data() + first;
      double* const vals = scratch_vals_.data() + first;
      int count = 1;  // the diagonal at 0
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
          cols[count] = row_of_[j];
          vals[count] = static_cast<double>(-c * w);
          ++count;
        } else {
          anchored_[static_cast<std::size_t>(r)] = 1;  // a Dirichlet neighbour
        }
      }
      cols[0] = static_cast<int>(r);
      vals[0] = static_cast<double>(diag);
      for (int p = 1; p < count; ++p) {
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
      outer[r + 1] = count;
      b[r] = static_cast<double>(ghost - source[i]);
    }
    outer[0] = 0;
    for (std::int64_t r = 0; r < rows; ++r) outer[r + 1] += outer[r];
    a.resizeNonZeros(outer[rows]);

    // Pass 2: the rows copied into place.
    int* const cols = a.innerIndexPtr();
    double* const vals = a.valuePtr();
    MPSFSI_OMP(parallel for schedule(static))
    for (std::int64_t r = 0; r < rows; ++r) {
      const Offset first = list.begin(static_cast<std::size_t>(particle_of_row_[static_cast<std::size_t>(r)])) +
                           static_cast<Offset>(r);
      const int count = outer[r + 1] - outer[r];
      std::copy_n(scratch_cols_.data() + first, count, cols + outer[r]);
      std::copy_n(scratch_vals_.data() + first, count, vals + outer[r]);
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
  std::vector<int> scratch_cols_;  // pass 1's rows, before they are packed
  std::vector<double> scratch_vals_;
  std::vector<Index> enclosed_;
  std::size_t enclosed_fluid_ = 0;
};

}  // namespace MPSFSI_ABI
}  // namespace mpsfsi
