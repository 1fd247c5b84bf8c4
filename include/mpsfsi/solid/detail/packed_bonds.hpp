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

// The constants of the corrected model's force loop, laid out so that the loop runs over `Lanes`
// particles at once, one per SIMD lane. Particles are taken in groups of `Lanes` consecutive ones
// (group G holds particles Lanes G .. Lanes G + Lanes - 1); a group's row has as many slots as its
// particle with the most bonds, and slot k holds the k-th bond of every particle of the group,
// lane l for particle Lanes G + l. Per slot, `Lanes` neighbour indices and one contiguous block of
// `rows` x `Lanes` scalars: r0_ij (Dim rows), beta_ij, then beta_ij |r0_ij| (the bond viscosity's
// weight, BondViscosity). Per group, one block of the particles' M_i^+
// (DeformationFit::inverse_moment), its upper triangle, `moment_rows` x `Lanes` scalars. The fit
// coefficients g_ij = beta_ij M_i^+ phi(r0_ij) are not stored: the loop works with M_i^+ and
// phi(r0) (recomputed from r0), which takes about half the bytes a bond in 3D (about 56 against
// 108) and two thirds in 2D (46 against 68; docs/performance.md, the solid's force loop). A padding slot (a
// particle with fewer bonds than its group's longest row, or a lane past the last particle) points
// at the lane's own particle, or the last particle, with r0 = beta = 0, so everything it
// contributes is an exact zero; a lane past the last particle has M^+ = 0.
template <int Dim, class Scalar, int Lanes>
class PackedBonds {
 public:
  using fit_type = DeformationFit<Dim, Scalar>;
  static constexpr int width = fit_type::width;
  static constexpr int rows = Dim + 2;  // scalars per bond: r0, beta, beta |r0|
  static constexpr int moment_rows = width * (width + 1) / 2;
  static constexpr std::size_t lanes = Lanes;
  // Offsets of the quantities within a slot's block, in scalars.
  static constexpr int r0_at(int a) { return a * Lanes; }
  static constexpr int beta_at = Dim * Lanes;
  static constexpr int viscous_weight_at = (Dim + 1) * Lanes;  // beta |r0| = w0 / |r0| (bond viscosity)
  // Offset of M^+(a, b) = M^+(b, a) within a group's moment block, in scalars.
  static constexpr int moment_at(int a, int b) {
    return a <= b ? (a * width - a * (a - 1) / 2 + (b - a)) * Lanes : moment_at(b, a);
  }

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
    moment_.assign(groups * moment_rows * lanes, Scalar(0));
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

  // Copies particle i's neighbours, reference vectors, weights and M_i^+ again (after its bonds
  // were cut and its fit rebuilt).
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
        block[viscous_weight_at] = bonds.beta(b) * bonds.r0(b).norm();
      } else {
        neighbor_[s * lanes + lane] = static_cast<Index>(i);
        for (int r = 0; r < rows; ++r) block[r * Lanes] = 0;
      }
    }
    Scalar* const m = moment_.data() + (i / lanes) * moment_rows * lanes + lane;
    const auto& inverse = fit.inverse_moment(i);
    for (int a = 0; a < width; ++a)
      for (int b = a; b < width; ++b) m[moment_at(a, b)] = inverse(a, b);
  }

  std::size_t num_particles() const { return particles_; }
  std::size_t num_groups() const { return (particles_ + lanes - 1) / lanes; }
  Offset begin(std::size_t group) const { return first_[group]; }
  Offset end(std::size_t group) const { return first_[group + 1]; }
  // begin(g) for g = 0 .. num_groups(): the slots before each group.
  const Offset* group_offsets() const { return first_.data(); }
  std::size_t longest_row() const { return longest_; }
  // The largest |i - j| over all bonds (cutting bonds never raises it): a loop over particles
  // lo..hi-1 touches no particle outside [lo - bandwidth, hi + bandwidth).
  std::size_t bandwidth() const { return bandwidth_; }
  // Slot s's `Lanes` neighbour indices and its block of `rows` x `Lanes` scalars.
  const Index* neighbors(Offset s) const { return neighbor_.data() + static_cast<std::size_t>(s) * lanes; }
  const Scalar* block(Offset s) const { return data_.data() + static_cast<std::size_t>(s) * rows * lanes; }
  // Group g's block of moment_rows x `Lanes` scalars (moment_at).
  const Scalar* moments(std::size_t group) const { return moment_.data() + group * moment_rows * lanes; }

 private:
  std::size_t particles_ = 0;
  std::vector<Offset> first_{0};
  std::size_t longest_ = 0;
  std::size_t bandwidth_ = 0;
  std::vector<Scalar, Eigen::aligned_allocator<Scalar>> data_;  // aligned to the SIMD register
  std::vector<Scalar, Eigen::aligned_allocator<Scalar>> moment_;
  std::vector<Index> neighbor_;
};

}  // namespace detail
}  // namespace MPSFSI_ABI
}  // namespace mpsfsi
