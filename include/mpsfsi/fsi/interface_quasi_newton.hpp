// SPDX-License-Identifier: BSD-3-Clause
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <deque>
#include <vector>

#include <Eigen/Dense>

#include "mpsfsi/core/abi.hpp"
#include "mpsfsi/core/types.hpp"

namespace mpsfsi {
inline namespace MPSFSI_ABI {

// The interface quasi-Newton update with an inverse Jacobian from a least-squares model, IQN-ILS
// (Degroote, Bathe & Vierendeels 2009; docs/theory.md, section 4.6), on the interface load F of
// FsiCoupler. At iteration k of a step the coupler has the load F_k it gave the structure, the
// fluid's answer F~_k and the residual r_k = F~_k - F_k. Each iteration after the first adds the
// columns
//   v = r_k - r_{k-1},   w = F~_k - F~_{k-1};
// the next load is
//   F_{k+1} = F~_k + W c,   c = argmin |V c + r_k|,
// the secant model's root. Without a column (the first iteration of the first step) it relaxes,
// F_1 = F_0 + omega r_0. Columns of the last `reuse_steps` steps are kept: the fluid's response to
// the structure (its added mass) changes slowly, and the model of earlier steps makes the first
// iterations of the next one Newton-like. Nearly dependent columns get no weight: the column-
// pivoted QR's rank threshold (1e-10 relative) leaves them out of the solve. At most `max_columns`
// are kept, the oldest dropped first.
template <class Scalar = double>
class InterfaceQuasiNewtonModel {
 public:
  InterfaceQuasiNewtonModel(int reuse_steps = 0, int max_columns = 64)
      : reuse_steps_(std::max(0, reuse_steps)), max_columns_(std::max(1, max_columns)) {}

  // Marks the start of a coupled step: differences are taken within a step only, and columns
  // older than reuse_steps steps are dropped.
  void begin_step() {
    ++step_;
    have_previous_ = false;
    while (!columns_.empty() && columns_.front().step < step_ - reuse_steps_) columns_.pop_front();
  }

  // Replaces `load` (F_k) by F_{k+1}, given the fluid's answer `trial` (F~_k) and `residual` (r_k).
  template <int Dim>
  void next_load(VecArray<Dim, Scalar>& load, const VecArray<Dim, Scalar>& trial, const VecArray<Dim, Scalar>& residual,
                 Scalar relaxation) {
    const auto n = static_cast<Eigen::Index>(Dim * load.size());
    const Eigen::Map<const Eigen::Matrix<Scalar, Eigen::Dynamic, 1>> r(residual.data()->data(), n);
    const Eigen::Map<const Eigen::Matrix<Scalar, Eigen::Dynamic, 1>> ft(trial.data()->data(), n);
    if (have_previous_) {
      columns_.push_back({r - previous_residual_, ft - previous_trial_, step_});
      if (static_cast<int>(columns_.size()) > max_columns_) columns_.pop_front();
    }
    previous_residual_ = r;
    previous_trial_ = ft;
    have_previous_ = true;
    Eigen::Map<Eigen::Matrix<Scalar, Eigen::Dynamic, 1>> f(load.data()->data(), n);
    if (columns_.empty()) {
      f += relaxation * r;
      return;
    }
    const auto m = static_cast<Eigen::Index>(columns_.size());
    v_.resize(n, m);
    w_.resize(n, m);
    for (Eigen::Index j = 0; j < m; ++j) {  // newest first
      const auto& c = columns_[static_cast<std::size_t>(m - 1 - j)];
      v_.col(j) = c.v;
      w_.col(j) = c.w;
    }
    qr_.compute(v_);
    qr_.setThreshold(Scalar(1e-10));
    const Eigen::Matrix<Scalar, Eigen::Dynamic, 1> coefficients = qr_.solve(Eigen::Matrix<Scalar, Eigen::Dynamic, 1>(-r));
    f = ft + w_ * coefficients;
  }

  std::size_t columns() const { return columns_.size(); }

  // Checkpoints (io/checkpoint.hpp): the step counter and the columns kept for the next steps;
  // the rest is rebuilt within a step.
  template <class Archive>
  void checkpoint_state(Archive& a) {
    a.value(step_);
    std::uint64_t count = columns_.size();
    a.value(count);  // overwritten when reading
    columns_.resize(static_cast<std::size_t>(count));
    for (auto& c : columns_) {
      a.value(c.step);
      exchange(a, c.v);
      exchange(a, c.w);
    }
  }

 private:
  // Writes or reads a dynamic vector through a flat copy (the archive takes std::vector).
  template <class Archive>
  static void exchange(Archive& a, Eigen::Matrix<Scalar, Eigen::Dynamic, 1>& v) {
    std::vector<Scalar> flat(v.data(), v.data() + v.size());
    a.array(flat);
    v = Eigen::Map<const Eigen::Matrix<Scalar, Eigen::Dynamic, 1>>(flat.data(), static_cast<Eigen::Index>(flat.size()));
  }

  struct Column {
    Eigen::Matrix<Scalar, Eigen::Dynamic, 1> v, w;
    long long step = 0;
  };
  int reuse_steps_, max_columns_;
  long long step_ = 0;
  bool have_previous_ = false;
  std::deque<Column> columns_;
  Eigen::Matrix<Scalar, Eigen::Dynamic, 1> previous_residual_, previous_trial_;
  Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic> v_, w_;
  Eigen::ColPivHouseholderQR<Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic>> qr_;
};

}  // namespace MPSFSI_ABI
}  // namespace mpsfsi
