// SPDX-License-Identifier: BSD-3-Clause
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "mpsfsi/core/abi.hpp"
#include "mpsfsi/core/types.hpp"

namespace mpsfsi {
inline namespace MPSFSI_ABI {

// How a particle's motion is constrained.
enum class Constraint : std::int32_t {
  free = 0,
  prescribed = 1,  // moves with a velocity the user sets (zero: clamped)
  support = 2,     // no velocity along a given direction (a simple support / roller)
};

// The constraint of each particle of a solid and its datum: the velocity of a prescribed
// particle, the unit normal of a supported one. ElasticSolver applies it to the velocities of
// every step (constrained) and reports the force it takes (reaction).
template <int Dim>
class ParticleConstraints {
 public:
  using vec_type = Vec<Dim, double>;

  // n free particles.
  void reset(std::size_t n) {
    kind_.assign(n, Constraint::free);
    datum_.assign(n, vec_type::Zero());
  }
  bool sized_for(std::size_t n) const { return kind_.size() == n && datum_.size() == n; }

  Constraint at(std::size_t i) const { return kind_[i]; }
  // The velocity of a prescribed particle (at(i) == Constraint::prescribed; for the others its
  // datum means something else).
  const vec_type& prescribed_velocity(std::size_t i) const { return datum_[i]; }
  void prescribe(std::size_t i, const vec_type& velocity) { set(i, Constraint::prescribed, velocity); }
  // No velocity along `normal` (finite, non-zero: the caller checks).
  void support(std::size_t i, const vec_type& normal) { set(i, Constraint::support, normal.normalized()); }
  void release(std::size_t i) { set(i, Constraint::free, vec_type::Zero()); }

  // The velocity v of particle i as its constraint allows it.
  vec_type constrained(std::size_t i, const vec_type& v) const {
    switch (kind_[i]) {
      case Constraint::prescribed: return datum_[i];
      case Constraint::support: return v - v.dot(datum_[i]) * datum_[i];
      default: return v;
    }
  }
  // The force the constraint exerts on particle i when the other forces on it sum to `applied`.
  vec_type reaction(std::size_t i, const vec_type& applied) const {
    switch (kind_[i]) {
      case Constraint::prescribed: return -applied;
      case Constraint::support: return -applied.dot(datum_[i]) * datum_[i];
      default: return vec_type::Zero();
    }
  }

  template <class Archive>
  void checkpoint_state(Archive& a) {
    a.array(kind_);
    a.array(datum_);
  }

 private:
  void set(std::size_t i, Constraint kind, const vec_type& datum) {
    kind_[i] = kind;
    datum_[i] = datum;
  }

  std::vector<Constraint> kind_;
  VecArray<Dim, double> datum_;  // the velocity, or the unit normal of a support
};

}  // namespace MPSFSI_ABI
}  // namespace mpsfsi
