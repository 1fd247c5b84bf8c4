// SPDX-License-Identifier: BSD-3-Clause
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "mpsfsi/core/abi.hpp"
#include "mpsfsi/core/parallel.hpp"
#include "mpsfsi/core/types.hpp"
#include "mpsfsi/solid/bonds.hpp"
#include "mpsfsi/solid/deformation.hpp"

namespace mpsfsi {
inline namespace MPSFSI_ABI {
namespace detail {

// The per-bond constants of the corrected model's force loop, laid out so that the loop runs over
// `Lanes` particles at once, one per SIMD lane. Particles are taken in groups of `Lanes`
// consecutive ones (group G holds particles Lanes G .. Lanes G + Lanes - 1); a group's row has as
// many slots as its particle with the most bonds, and slot k holds the k-th bond of every particle
// of the group, lane l for particle Lanes G + l. Per slot, `Lanes` neighbour indices and one
// contiguous block of `rows` x `Lanes` scalars: r0_ij (Dim rows), beta_ij, then the fit
// coefficients g_ij (DeformationFit::width rows), so the loop streams one array and loads every
// quantity of a slot as one register. The quadratic part of phi(r0) is not stored but recomputed
// from r0 in the loop: at 1e4 particles and more the step is limited by memory traffic. A padding
// slot (a particle with fewer bonds than its group's longest row, or a lane past the last
// particle) points at the lane's own particle, or the last particle, with r0 = beta = g = 0, so
// everything it contributes is an exact zero.
template <int Dim, class Scalar, int Lanes>
class PackedBonds {
 public:
  using fit_type = DeformationFit<Dim, Scalar>;
  static constexpr int width = fit_type::width;
  static constexpr int rows = Dim + 1 + width;  // scalars per bond: r0, beta, g
  static constexpr std::size_t lanes = Lanes;
  // Offsets of the quantities within a slot's block, in scalars.
  static constexpr int r0_at(int a) { return a * Lanes; }
  static constexpr int beta_at = Dim * Lanes;
  static constexpr int coefficient_at(int c) { return (Dim + 1 + c) * Lanes; }

  void build(const fit_type& fit, const BondList<Dim, Scalar>& bonds) {
    particles_ = bonds.num_particles();
    const std::size_t groups = num_groups();
    first_.assign(groups + 1, 0);
    longest_ = 0;
    for (std::size_t g = 0; g < groups; ++g) {
      Offset row = 0;
      for (std::size_t i = g * lanes; i < std::min(particles_, (g + 1) * lanes); ++i)
        row = std::max(row, bonds.end(i) - bonds.begin(i));
      first_[g + 1] = first_[g] + row;
      longest_ = std::max(longest_, static_cast<std::size_t>(row));
    }
    const auto slots = static_cast<std::size_t>(first_[groups]);
    data_.assign(slots * rows * lanes, Scalar(0));
    neighbor_.resize(slots * lanes);
    std::size_t band = 0;
    MPSFSI_OMP(parallel for schedule(static) reduction(max : band))
    for (std::int64_t ii = 0; ii < static_cast<std::int64_t>(groups * lanes); ++ii) {
      const auto i = static_cast<std::size_t>(ii);
      const std::size_t owner = std::min(i, particles_ - 1);  // a lane past the last particle: the last
      if (i < particles_) update(fit, bonds, i);
      for (Offset s = first_[i / lanes]; s < first_[i / lanes + 1]; ++s) {
        Index& j = neighbor_[static_cast<std::size_t>(s) * lanes + i % lanes];
        if (i >= particles_) j = static_cast<Index>(owner);
        const auto k = static_cast<std::size_t>(j);
        band = std::max(band, k > owner ? k - owner : owner - k);
      }
    }
    bandwidth_ = band;
  }

  // Copies particle i's neighbours, weights and coefficients again (after its bonds were cut and
  // its fit rebuilt).
  void update(const fit_type& fit, const BondList<Dim, Scalar>& bonds, std::size_t i) {
    const std::size_t lane = i % lanes;
    const Offset first = first_[i / lanes];
    const Offset count = bonds.end(i) - bonds.begin(i);
    for (Offset k = 0; k < first_[i / lanes + 1] - first; ++k) {
      const auto s = static_cast<std::size_t>(first + k);
      Scalar* const block = data_.data() + s * rows * lanes + lane;
      if (k < count) {
        const Offset b = bonds.begin(i) + k;
        neighbor_[s * lanes + lane] = bonds.neighbor(b);
        for (int a = 0; a < Dim; ++a) block[r0_at(a)] = bonds.r0(b)[a];
        block[beta_at] = bonds.beta(b);
        const auto& g = fit.coefficients()[static_cast<std::size_t>(b)];
        for (int c = 0; c < width; ++c) block[coefficient_at(c)] = g[c];
      } else {
        neighbor_[s * lanes + lane] = static_cast<Index>(i);
        for (int r = 0; r < rows; ++r) block[r * Lanes] = 0;
      }
    }
  }

  std::size_t num_particles() const { return particles_; }
  std::size_t num_groups() const { return (particles_ + lanes - 1) / lanes; }
  Offset begin(std::size_t group) const { return first_[group]; }
  Offset end(std::size_t group) const { return first_[group + 1]; }
  std::size_t longest_row() const { return longest_; }
  // The largest |i - j| over all bonds (cutting bonds never raises it): a loop over particles
  // lo..hi-1 touches no particle outside [lo - bandwidth, hi + bandwidth).
  std::size_t bandwidth() const { return bandwidth_; }
  // Slot s's `Lanes` neighbour indices and its block of `rows` x `Lanes` scalars.
  const Index* neighbors(Offset s) const { return neighbor_.data() + static_cast<std::size_t>(s) * lanes; }
  const Scalar* block(Offset s) const { return data_.data() + static_cast<std::size_t>(s) * rows * lanes; }

 private:
  std::size_t particles_ = 0;
  std::vector<Offset> first_{0};
  std::size_t longest_ = 0;
  std::size_t bandwidth_ = 0;
  std::vector<Scalar, Eigen::aligned_allocator<Scalar>> data_;  // aligned to the SIMD register
  std::vector<Index> neighbor_;
};

}  // namespace detail
}  // namespace MPSFSI_ABI
}  // namespace mpsfsi
