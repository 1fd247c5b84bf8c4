// SPDX-License-Identifier: BSD-3-Clause
#pragma once

#include <cstdint>
#include <vector>

#include "mpsfsi/core/neighbor_list.hpp"
#include "mpsfsi/core/parallel.hpp"
#include "mpsfsi/core/particle_set.hpp"
#include "mpsfsi/core/types.hpp"
#include "mpsfsi/fluid/linear_solver.hpp"
#include "mpsfsi/kernels/detail/pair.hpp"
#include "mpsfsi/kernels/lattice_constants.hpp"

namespace mpsfsi {

// The pressure Poisson equation, eq 11, discretised with the MPS Laplacian:
//   (2d/(lambda n0)) sum_j w_ij (P_j - P_i) = s_i,
// negated into the symmetric positive definite system
//   A_ii = c sum_j w_ij,  A_ij = -c w_ij,  b_i = -s_i,   c = 2d/(lambda n0),
// over the unknowns: fluid and wall particles not at the free surface. Neighbours at the free
// surface (P = 0, Dirichlet) add to the diagonal only; dummy particles are not in the PPE and
// must already be absent from `list` (FluidSolver passes its fluid-and-wall list).
// Assembled straight into CSR: one counting pass, a prefix sum, one filling pass, OpenMP over
// rows, each row sorted by column. The arrays keep their capacity from one step to the next.
template <class Weight, int Dim, class Scalar>
class PpeAssembler {
 public:
  // Unknown number of particle i, or -1 if it is not an unknown.
  const std::vector<Index>& row_of() const { return row_of_; }
  const std::vector<Index>& particle_of_row() const { return particle_of_row_; }
  std::size_t num_unknowns() const { return particle_of_row_.size(); }

  void assemble(const VecArray<Dim, Scalar>& x, const std::vector<ParticleKind>& kinds,
                const std::vector<std::uint8_t>& surface, const BasicNeighborList<Scalar>& list,
                const MpsConstants<Scalar>& lap, const std::vector<Scalar>& source, PpeMatrix& a, PpeVector& b) {
    const std::size_t n = x.size();
    detail::require_list_rows(list, n, "PpeAssembler::assemble");
    row_of_.resize(n);
    particle_of_row_.clear();
    for (std::size_t i = 0; i < n; ++i) {
      const bool unknown = kinds[i] != ParticleKind::dummy && kinds[i] != ParticleKind::solid && !surface[i];
      row_of_[i] = unknown ? static_cast<Index>(particle_of_row_.size()) : Index(-1);
      if (unknown) particle_of_row_.push_back(static_cast<Index>(i));
    }
    const auto rows = static_cast<std::int64_t>(particle_of_row_.size());
    a.resize(rows, rows);
    b.resize(rows);
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
    for (std::int64_t r = 0; r < rows; ++r) outer[r + 1] += outer[r];
    a.resizeNonZeros(outer[rows]);
    int* cols = a.innerIndexPtr();
    double* vals = a.valuePtr();

    // Pass 2: values; the row is then insertion-sorted by column (rows hold ~30 entries).
    const Scalar c = Scalar(2 * Dim) / (lap.lambda * lap.n0);
    MPSFSI_OMP(parallel for schedule(static))
    for (std::int64_t r = 0; r < rows; ++r) {
      const auto i = static_cast<std::size_t>(particle_of_row_[static_cast<std::size_t>(r)]);
      int pos = outer[r];
      const int diag_pos = pos++;
      Scalar diag = 0;
      for (Offset k = list.begin(i); k < list.end(i); ++k) {
        const auto j = static_cast<std::size_t>(list.indices[k]);
        if (kinds[j] == ParticleKind::dummy) continue;
        const Vec<Dim, Scalar> rij = x[j] - x[i];
        const Scalar w = Weight::value(detail::pair_distance(list, k, rij), lap.re);
        if (!(w > 0)) continue;
        diag += c * w;
        if (row_of_[j] >= 0) {
          cols[pos] = row_of_[j];
          vals[pos] = static_cast<double>(-c * w);
          ++pos;
        }
      }
      cols[diag_pos] = static_cast<int>(r);
      vals[diag_pos] = static_cast<double>(diag);
      for (int p = outer[r] + 1; p < outer[r + 1]; ++p) {
        const int col = cols[p];
        const double val = vals[p];
        int q = p - 1;
        for (; q >= outer[r] && cols[q] > col; --q) {
          cols[q + 1] = cols[q];
          vals[q + 1] = vals[q];
        }
        cols[q + 1] = col;
        vals[q + 1] = val;
      }
      b[r] = static_cast<double>(-source[i]);
    }
  }

 private:
  std::vector<Index> row_of_;
  std::vector<Index> particle_of_row_;
};

}  // namespace mpsfsi
