// SPDX-License-Identifier: BSD-3-Clause
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "mpsfsi/core/parallel.hpp"
#include "mpsfsi/core/types.hpp"
#include "mpsfsi/solid/bonds.hpp"
#include "mpsfsi/solid/deformation.hpp"

namespace mpsfsi::detail {

// The per-bond constants of the corrected model's force loop in structure-of-arrays form, with
// each particle's row of bonds padded to a whole number of SIMD lanes (`Lanes` bonds), so the loop
// over one particle's bonds runs `Lanes` bonds at a time with no remainder. Per slot: the
// neighbour j, r0_ij (Dim rows), beta_ij and the fit coefficients g_ij (DeformationFit::width
// rows). The quadratic part of phi(r0) is not stored but recomputed from r0 in the loop: at 1e4
// particles and more the step is limited by memory traffic. A padding slot points at its own
// particle with r0 = beta = g = 0, so everything it contributes is an exact zero.
template <int Dim, class Scalar, int Lanes>
class PackedBonds {
 public:
  using fit_type = DeformationFit<Dim, Scalar>;
  static constexpr int width = fit_type::width;

  void build(const fit_type& fit, const BondList<Dim, Scalar>& bonds) {
    const std::size_t n = bonds.num_particles();
    first_.assign(n + 1, 0);
    longest_ = 0;
    for (std::size_t i = 0; i < n; ++i) {
      const Offset row = padded(bonds.end(i) - bonds.begin(i));
      first_[i + 1] = first_[i] + row;
      longest_ = std::max(longest_, static_cast<std::size_t>(row));
    }
    slots_ = static_cast<std::size_t>(first_[n]);
    data_.assign(static_cast<std::size_t>(rows) * slots_, Scalar(0));
    neighbor_.resize(slots_);
    std::size_t band = 0;
    MPSFSI_OMP(parallel for schedule(static) reduction(max : band))
    for (std::int64_t ii = 0; ii < static_cast<std::int64_t>(n); ++ii) {
      const auto i = static_cast<std::size_t>(ii);
      for (Offset s = first_[i]; s < first_[i + 1]; ++s) {
        const Offset b = bonds.begin(i) + (s - first_[i]);
        const auto k = static_cast<std::size_t>(s);
        neighbor_[k] = b < bonds.end(i) ? bonds.neighbor(b) : static_cast<Index>(i);
        const auto j = static_cast<std::size_t>(neighbor_[k]);
        band = std::max(band, j > i ? j - i : i - j);
      }
      update(fit, bonds, i);
    }
    bandwidth_ = band;
  }

  // Copies particle i's weights and coefficients again (after its bonds were cut and its fit
  // rebuilt).
  void update(const fit_type& fit, const BondList<Dim, Scalar>& bonds, std::size_t i) {
    Offset s = first_[i];
    for (Offset b = bonds.begin(i); b < bonds.end(i); ++b, ++s) {
      const auto k = static_cast<std::size_t>(s);
      for (int a = 0; a < Dim; ++a) data_[static_cast<std::size_t>(a) * slots_ + k] = bonds.r0(b)[a];
      data_[static_cast<std::size_t>(Dim) * slots_ + k] = bonds.beta(b);
      const auto& g = fit.coefficients()[static_cast<std::size_t>(b)];
      for (int c = 0; c < width; ++c) data_[static_cast<std::size_t>(Dim + 1 + c) * slots_ + k] = g[c];
    }
  }

  Offset begin(std::size_t i) const { return first_[i]; }
  Offset end(std::size_t i) const { return first_[i + 1]; }
  std::size_t longest_row() const { return longest_; }
  // The largest |i - j| over all bonds (cutting bonds never raises it): a loop over particles
  // lo..hi-1 touches no particle outside [lo - bandwidth, hi + bandwidth).
  std::size_t bandwidth() const { return bandwidth_; }
  const Index* neighbors() const { return neighbor_.data(); }
  const Scalar* reference_vector(int a) const { return row(a); }
  const Scalar* beta() const { return row(Dim); }
  const Scalar* coefficient(int c) const { return row(Dim + 1 + c); }

 private:
  static constexpr int rows = Dim + 1 + width;
  static Offset padded(Offset count) { return (count + Lanes - 1) / Lanes * Lanes; }
  const Scalar* row(int r) const { return data_.data() + static_cast<std::size_t>(r) * slots_; }

  std::vector<Offset> first_{0};
  std::size_t slots_ = 0;
  std::size_t longest_ = 0;
  std::size_t bandwidth_ = 0;
  std::vector<Scalar> data_;
  std::vector<Index> neighbor_;
};

}  // namespace mpsfsi::detail
