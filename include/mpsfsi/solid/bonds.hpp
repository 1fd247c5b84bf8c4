// SPDX-License-Identifier: BSD-3-Clause
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "mpsfsi/core/abi.hpp"
#include "mpsfsi/core/cell_list_search.hpp"
#include "mpsfsi/core/error.hpp"
#include "mpsfsi/core/neighbor_list.hpp"
#include "mpsfsi/core/parallel.hpp"
#include "mpsfsi/core/types.hpp"
#include "mpsfsi/kernels/weight.hpp"

namespace mpsfsi {
inline namespace MPSFSI_ABI {

// The fixed bonds of a total-Lagrangian solid (docs/theory.md, section 3.2): every pair of particles
// of the same body closer than re in the reference configuration, stored per particle in CSR form
// with j ascending. Each directed bond keeps its reference vector r0_ij = X_j - X_i and the weight
// ratio beta_ij = w(|r0_ij|) / |r0_ij|^2 that every structure sum uses. Bonds are symmetric: (i, j)
// and (j, i) are both stored and `reverse(b)` links them. A cut bond (fracture) gets beta = 0 and
// `intact(b) = false` in both directions; it never heals.
template <int Dim, class Scalar = double>
class BondList {
 public:
  using vec_type = Vec<Dim, Scalar>;

  BondList() = default;

  // Builds the bonds of `reference` (positions X) within radius re, only between particles with
  // the same body id. Throws InvalidInput if two bonded particles coincide.
  template <class Weight>
  void build(const VecArray<Dim, Scalar>& reference, const std::vector<std::int32_t>& body, Scalar re) {
    check_weight<Weight>();
    const std::size_t n = reference.size();
    if (body.size() != n) detail::throw_invalid("BondList", "body ids and positions differ in size");
    CellListSearch<Dim, Scalar> search(re);
    search.build(reference);
    BasicNeighborList<Scalar> all;
    search.self_query(reference, all, QueryOptions{true});
    offsets_.assign(n + 1, 0);
    for (std::size_t i = 0; i < n; ++i) {
      Offset count = 0;
      for (Offset k = all.begin(i); k < all.end(i); ++k)
        if (body[static_cast<std::size_t>(all.indices[k])] == body[i] && all.distances[k] < re) ++count;
      offsets_[i + 1] = offsets_[i] + count;
    }
    const auto m = static_cast<std::size_t>(offsets_[n]);
    neighbor_.resize(m);
    r0_.resize(m);
    beta_.resize(m);
    intact_.assign(m, 1);
    for (std::size_t i = 0; i < n; ++i) {
      std::vector<std::pair<Index, Scalar>> row;
      for (Offset k = all.begin(i); k < all.end(i); ++k) {
        const auto j = static_cast<std::size_t>(all.indices[k]);
        if (body[j] == body[i] && all.distances[k] < re) row.emplace_back(all.indices[k], all.distances[k]);
      }
      std::sort(row.begin(), row.end());
      Offset b = offsets_[i];
      for (const auto& [j, r] : row) {
        if (!(r > Scalar(1e-9) * re))
          detail::throw_invalid("BondList", "particles " + std::to_string(i) + " and " + std::to_string(j) +
                                                " coincide in the reference configuration");
        neighbor_[static_cast<std::size_t>(b)] = j;
        r0_[static_cast<std::size_t>(b)] = reference[static_cast<std::size_t>(j)] - reference[i];
        beta_[static_cast<std::size_t>(b)] = Weight::value(r, re) / (r * r);
        ++b;
      }
    }
    // Reverse links: the bonds are symmetric because the distance test is.
    reverse_.resize(m);
    for (std::size_t i = 0; i < n; ++i)
      for (Offset b = offsets_[i]; b < offsets_[i + 1]; ++b) {
        const auto j = static_cast<std::size_t>(neighbor_[static_cast<std::size_t>(b)]);
        const auto first = neighbor_.begin() + offsets_[j], last = neighbor_.begin() + offsets_[j + 1];
        const auto it = std::lower_bound(first, last, static_cast<Index>(i));
        reverse_[static_cast<std::size_t>(b)] = static_cast<Offset>(it - neighbor_.begin());
      }
    initial_count_.resize(n);
    for (std::size_t i = 0; i < n; ++i) initial_count_[i] = static_cast<Index>(offsets_[i + 1] - offsets_[i]);
    intact_count_ = initial_count_;
  }

  std::size_t num_particles() const { return offsets_.empty() ? 0 : offsets_.size() - 1; }
  std::size_t num_bonds() const { return neighbor_.size(); }  // directed: each pair twice
  Offset begin(std::size_t i) const { return offsets_[i]; }
  Offset end(std::size_t i) const { return offsets_[i + 1]; }
  Index neighbor(Offset b) const { return neighbor_[static_cast<std::size_t>(b)]; }
  const vec_type& r0(Offset b) const { return r0_[static_cast<std::size_t>(b)]; }
  Scalar beta(Offset b) const { return beta_[static_cast<std::size_t>(b)]; }
  // The reference weight w(|r0_ij|) (zero once cut).
  Scalar weight(Offset b) const { return beta(b) * r0(b).squaredNorm(); }
  bool intact(Offset b) const { return intact_[static_cast<std::size_t>(b)] != 0; }
  Offset reverse(Offset b) const { return reverse_[static_cast<std::size_t>(b)]; }

  // Raw arrays for hot loops.
  const std::vector<Offset>& offsets() const { return offsets_; }
  const std::vector<Index>& neighbors() const { return neighbor_; }
  const VecArray<Dim, Scalar>& reference_vectors() const { return r0_; }
  const std::vector<Scalar>& betas() const { return beta_; }
  const std::vector<Offset>& reverse_links() const { return reverse_; }

  Index initial_count(std::size_t i) const { return initial_count_[i]; }
  Index intact_count(std::size_t i) const { return intact_count_[i]; }

  // Fraction of particle i's initial bonds that are cut (0 for a particle that had none).
  Scalar damage(std::size_t i) const {
    return initial_count_[i] == 0 ? Scalar(0)
                                  : Scalar(1) - Scalar(intact_count_[i]) / Scalar(initial_count_[i]);
  }

  // Whether i and j are joined by an intact bond (binary search in i's row).
  bool bonded(std::size_t i, Index j) const {
    const auto first = neighbor_.begin() + offsets_[i], last = neighbor_.begin() + offsets_[i + 1];
    const auto it = std::lower_bound(first, last, j);
    return it != last && *it == j && intact_[static_cast<std::size_t>(it - neighbor_.begin())] != 0;
  }

  // Cuts bond b and its reverse. Returns false if it was already cut. Not thread-safe.
  bool cut(Offset b) {
    if (!intact(b)) return false;
    const Offset r = reverse(b);
    for (const Offset e : {b, r}) {
      intact_[static_cast<std::size_t>(e)] = 0;
      beta_[static_cast<std::size_t>(e)] = 0;
    }
    --intact_count_[static_cast<std::size_t>(neighbor_[static_cast<std::size_t>(r)])];
    --intact_count_[static_cast<std::size_t>(neighbor_[static_cast<std::size_t>(b)])];
    ++cut_count_;
    return true;
  }

  std::size_t num_cut() const { return cut_count_; }  // pairs

  // Checkpoints (io/checkpoint.hpp): which bonds are cut. The bond graph itself is rebuilt from
  // the reference positions by the solver that reads.
  template <class Archive>
  void checkpoint_state(Archive& a) {
    const std::size_t bonds = neighbor_.size(), particles = intact_count_.size();
    a.array(beta_);
    a.array(intact_);
    a.array(intact_count_);
    a.value(cut_count_);
    if (beta_.size() != bonds || intact_.size() != bonds || intact_count_.size() != particles)
      detail::throw_invalid("BondList::checkpoint_state", "the checkpoint's bonds do not match this solid's");
  }

 private:
  std::vector<Offset> offsets_{0};
  std::vector<Index> neighbor_;
  VecArray<Dim, Scalar> r0_;
  std::vector<Scalar> beta_;
  std::vector<std::uint8_t> intact_;
  std::vector<Offset> reverse_;
  std::vector<Index> initial_count_, intact_count_;
  std::size_t cut_count_ = 0;
};

}  // namespace MPSFSI_ABI
}  // namespace mpsfsi
