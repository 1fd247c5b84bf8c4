// SPDX-License-Identifier: BSD-3-Clause
#pragma once

#include <algorithm>
#include <cstdint>
#include <string>
#include <unordered_map>
#include <vector>

#include "mpsfsi/core/abi.hpp"
#include "mpsfsi/core/detail/format.hpp"
#include "mpsfsi/core/error.hpp"
#include "mpsfsi/core/parallel.hpp"
#include "mpsfsi/core/types.hpp"

namespace mpsfsi {
inline namespace MPSFSI_ABI {
namespace detail {

// ElasticSolver's blow-up check. A step blows up where a new position or velocity is not finite
// or a particle would move faster than a limit (blowup_speed_factor times the P-wave speed)
// relative to the mean velocity of its body. Relative, because no elastic wave carries a particle
// past its neighbours that fast, while a body may translate or turn rigidly at any speed.
template <int Dim>
class BodyBlowupCheck {
 public:
  using vec_type = Vec<Dim, double>;

  // Dense body numbers 0, 1, ... in order of first appearance, and the particle count of each.
  explicit BodyBlowupCheck(const std::vector<std::int32_t>& body) {
    std::unordered_map<std::int32_t, std::size_t> number;
    body_index_.resize(body.size());
    for (std::size_t i = 0; i < body.size(); ++i) {
      const auto [it, added] = number.try_emplace(body[i], number.size());
      if (added) body_size_.push_back(0);
      body_index_[i] = it->second;
      body_size_[it->second] += 1;
    }
    body_velocity_.assign(number.size(), vec_type::Zero());
  }
  BodyBlowupCheck() = default;

  // Throws SimulationError naming the step, the time and the particle (index and id) if the
  // proposed positions x and velocities v of step `step` (ending at `time`) blow up.
  void check(const VecArray<Dim, double>& x, const VecArray<Dim, double>& v, const std::vector<Index>& ids,
             double limit, long long step, double time) {
    const std::size_t n = v.size();
    std::fill(body_velocity_.begin(), body_velocity_.end(), vec_type::Zero());
    for (std::size_t i = 0; i < n; ++i) body_velocity_[body_index_[i]] += v[i];  // one pass, O(n)
    for (std::size_t b = 0; b < body_velocity_.size(); ++b) body_velocity_[b] /= body_size_[b];
    long long bad = -1;
    MPSFSI_OMP(parallel for schedule(static))
    for (std::int64_t ii = 0; ii < static_cast<std::int64_t>(n); ++ii) {
      const auto i = static_cast<std::size_t>(ii);
      const bool finite = x[i].allFinite() && v[i].allFinite();
      if (!finite || !((v[i] - body_velocity_[body_index_[i]]).norm() <= limit)) {
        MPSFSI_OMP(atomic write)
        bad = static_cast<long long>(i);
      }
    }
    if (bad < 0) return;
    const auto i = static_cast<std::size_t>(bad);
    const vec_type relative = v[i] - body_velocity_[body_index_[i]];
    const std::string what =
        !x[i].allFinite() || !v[i].allFinite()
            ? std::string("its position or velocity is not finite")
            : "it would move at " + format_number(relative.norm()) + " m/s relative to its body (" +
                  format_number(v[i].norm()) + " m/s absolute), limit " + format_number(limit) +
                  " m/s (the P-wave speed times blowup_speed_factor)";
    throw SimulationError("ElasticSolver: blow-up at step " + std::to_string(step) + " (t = " + format_number(time) +
                              " s): particle " + std::to_string(i) + " (id " + std::to_string(ids[i]) + "): " + what,
                          step, time, bad);
  }

 private:
  std::vector<std::size_t> body_index_;  // dense body number of each particle
  std::vector<double> body_size_;        // particles per body
  VecArray<Dim, double> body_velocity_;  // mean velocity per body
};

}  // namespace detail
}  // namespace MPSFSI_ABI
}  // namespace mpsfsi
