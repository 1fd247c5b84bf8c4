// SPDX-License-Identifier: BSD-3-Clause
#pragma once

#include <cstddef>
#include <limits>
#include <type_traits>
#include <utility>
#include <vector>

#include "mpsfsi/core/abi.hpp"
#include "mpsfsi/core/particle_set.hpp"
#include "mpsfsi/core/types.hpp"

namespace mpsfsi {
inline namespace MPSFSI_ABI {

// ElasticSolver's failure slot, as far as a solid that never breaks needs it. The failure models
// that break bonds, and the process that reads their stress and cuts (FractureProcess), are in
// fracture/: a solid built with NoFailure includes none of it.

// Null object: nothing ever fails (the solver skips the check entirely).
struct NoFailure {
  static constexpr bool enabled = false;
  template <int Dim, class Scalar>
  static Scalar principal(const Mat<Dim, Scalar>&, Vec<Dim, Scalar>& direction) {
    direction = Vec<Dim, Scalar>::UnitX();
    return -std::numeric_limits<Scalar>::infinity();
  }
};

// One particle failing (eq 27): when, which particle, sigma_1 and the crack-plane normal (with a
// one-sided SolidParameters::crack_side, pointing to the side the particle stayed with).
template <int Dim>
struct FailureEvent {
  double time = 0;
  std::size_t particle = 0;
  double sigma1 = 0;
  Vec<Dim, double> normal = Vec<Dim, double>::Zero();
};

// The fracture process of a failure model with `enabled = true`: defined in
// fracture/fracture_process.hpp, which such a solver's translation unit includes.
template <int Dim, class Failure>
class FractureProcess;

// What ElasticSolver holds in its place when nothing can fail: the model object and an empty
// record.
template <int Dim, class Failure>
class NoFractureProcess {
 public:
  explicit NoFractureProcess(Failure failure) : failure_(std::move(failure)) {}
  const Failure& model() const { return failure_; }
  const std::vector<FailureEvent<Dim>>& log() const { return log_; }
  double first_failure_time() const { return -1; }
  const std::vector<double>& strengths(const ParticleSet<Dim>&) const { return none_; }
  template <class... Inputs>
  const std::vector<double>& criterion_stresses(const ParticleSet<Dim>&, const Inputs&...) const {
    return none_;
  }
  template <class... Inputs>
  void refresh_output(const ParticleSet<Dim>&, const Inputs&...) const {}
  // Nothing is read out, so no load needs a kind.
  void mark_distributed_load(std::size_t, std::size_t) {}
  template <class Archive>
  void checkpoint_state(Archive&) {}

 private:
  Failure failure_;
  std::vector<FailureEvent<Dim>> log_;
  std::vector<double> none_;
};

namespace detail {

template <class F, class = void>
struct has_failure_enabled : std::false_type {};
template <class F>
struct has_failure_enabled<F, std::void_t<decltype(bool(F::enabled))>> : std::true_type {};

template <class T, class = void>
struct is_complete : std::false_type {};
template <class T>
struct is_complete<T, std::void_t<decltype(sizeof(T))>> : std::true_type {};

}  // namespace detail

}  // namespace MPSFSI_ABI
}  // namespace mpsfsi
