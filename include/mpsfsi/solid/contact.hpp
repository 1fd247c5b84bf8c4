// SPDX-License-Identifier: BSD-3-Clause
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <optional>
#include <utility>
#include <vector>

#include "mpsfsi/core/abi.hpp"
#include "mpsfsi/core/cell_list_search.hpp"
#include "mpsfsi/core/error.hpp"
#include "mpsfsi/core/filter_neighbors.hpp"
#include "mpsfsi/core/neighbor_list.hpp"
#include "mpsfsi/core/parallel.hpp"
#include "mpsfsi/core/types.hpp"
#include "mpsfsi/solid/bonds.hpp"
#include "mpsfsi/solid/coulomb_friction.hpp"

namespace mpsfsi {
inline namespace MPSFSI_ABI {

// A contact policy of ElasticSolver provides
//   void initialize(std::size_t n, Scalar distance, Scalar stiffness, Scalar damping);
//   void add_forces(const VecArray& x, const VecArray& v, const BondList&, VecArray& force);  // adds
//   Scalar energy(const VecArray& x, const BondList&) const;
//   std::size_t active_pairs() const;
//   template <class Archive> void checkpoint_state(Archive&);  // checkpoints and iterative coupling

// No contact at all (a single body that never breaks, or a user who handles it elsewhere).
struct NoContact {
  template <class Scalar>
  void initialize(std::size_t, Scalar, Scalar, Scalar) {}
  template <class X, class B, class F>
  void add_forces(const X&, const X&, const B&, F&) {}
  template <class X>
  bool touching(const X&, std::size_t) const {
    return false;
  }
  template <class X, class B>
  double energy(const X&, const B&) const { return 0; }
  std::size_t active_pairs() const { return 0; }
  template <class Archive>
  void checkpoint_state(Archive&) {}
};

// Penalty contact between particles that are not joined by an intact bond:
//   f_i = [k (d_c - r) - c (v_i - v_j) . e] e,  e = (x_i - x_j)/r,  for r < d_c,
// a linear spring that only pushes (energy k (d_c - r)^2 / 2 per pair) with an optional normal
// dashpot c = 2 zeta sqrt(k m/2) (zeta = SolidParameters::contact_damping_ratio, 0 by default)
// for impacts that should not bounce, and Coulomb friction of coefficient mu
// (SolidParameters::contact_friction, 0 by default: frictionless; docs/theory.md, section 3.5).
// Friction is a tangential spring of the same stiffness k from where the pair's relative position
// was anchored when it came into contact, capped at mu times the normal force: a pair below the
// cap sticks, a pair at it slides, and sliding moves the anchor so that the spring stays at the
// cap (kinetic friction mu f_n, no dependence on the time step). It acts on the relative motion of
// the particle centres (particles carry no spin). Used at
// supports and indenters (other bodies) and between fragments after fracture (cut bonds). The
// candidate pairs are a Verlet list with a skin of half a spacing, rebuilt when some particle has
// moved more than half the skin since the last build or a bond has been cut since.
// Time step: a particle of mass m = rho l0^d on this spring oscillates at sqrt(k/m); with the
// default k = E l0^(d-2) that is sqrt(E/rho)/l0, slower than the P-wave limit for nu >= 0, and
// SolidParameters::signal_speed() accounts for it when the stiffness ratio is raised.
template <int Dim, class Scalar = double>
class PenaltyContact {
 public:
  using vec_type = Vec<Dim, Scalar>;

  void initialize(std::size_t n, Scalar distance, Scalar stiffness, Scalar damping) {
    distance_ = distance;
    stiffness_ = stiffness;
    damping_ = damping;
    skin_ = Scalar(0.5) * distance;
    built_at_.clear();
    list_.clear();
    anchor_.clear();
    stretch_.clear();
    held_.clear();
    (void)n;
  }

  // Coulomb friction coefficient mu >= 0 (0: frictionless). ElasticSolver sets it from
  // SolidParameters::contact_friction after initialize().
  void set_friction(Scalar mu) {
    if (!(mu >= 0) || !std::isfinite(mu))
      detail::throw_invalid("PenaltyContact::set_friction", "the friction coefficient must be finite and >= 0");
    friction_ = mu;
  }
  Scalar friction() const { return friction_; }

  void add_forces(const VecArray<Dim, Scalar>& x, const VecArray<Dim, Scalar>& v, const BondList<Dim, Scalar>& bonds,
                  VecArray<Dim, Scalar>& force) {
    if (stiffness_ == 0) return;
    if (needs_rebuild(x, bonds)) rebuild(x, bonds);
    const auto n = static_cast<std::int64_t>(x.size());
    const bool frictional = friction_ > 0;
    std::size_t active = 0;
    MPSFSI_OMP(parallel for schedule(static) reduction(+ : active))
    for (std::int64_t ii = 0; ii < n; ++ii) {
      const auto i = static_cast<std::size_t>(ii);
      vec_type f = vec_type::Zero();
      for (Offset k = list_.begin(i); k < list_.end(i); ++k) {
        const auto slot = static_cast<std::size_t>(k);
        const auto j = static_cast<std::size_t>(list_.indices[slot]);
        const vec_type r = x[i] - x[j];
        const Scalar d2 = r.squaredNorm();
        if (d2 >= distance_ * distance_ || d2 == 0) {
          if (frictional) held_[slot] = 0;
          continue;
        }
        const Scalar d = std::sqrt(d2);
        const vec_type e = r / d;
        const Scalar normal = stiffness_ * (distance_ - d) - damping_ * (v[i] - v[j]).dot(e);
        f += normal * e;
        if (frictional) f += friction_force(slot, r, e, normal);
        ++active;
      }
      force[i] += f;
    }
    active_ = active / 2;
  }

  Scalar energy(const VecArray<Dim, Scalar>& x, const BondList<Dim, Scalar>&) const {
    Scalar total = 0;
    for (std::size_t i = 0; i < list_.num_queries(); ++i)
      for (Offset k = list_.begin(i); k < list_.end(i); ++k) {
        const Scalar d = (x[i] - x[static_cast<std::size_t>(list_.indices[k])]).norm();
        if (d < distance_) total += Scalar(0.25) * stiffness_ * (distance_ - d) * (distance_ - d);  // each pair twice
      }
    return total + friction_energy();
  }

  // The energy held in the sticking friction springs, k |s|^2 / 2 per pair, s the tangential
  // stretch of the last add_forces (0 when frictionless).
  Scalar friction_energy() const {
    Scalar total = 0;
    for (std::size_t k = 0; k < held_.size(); ++k)
      if (held_[k]) total += Scalar(0.25) * stiffness_ * stretch_[k].squaredNorm();  // each pair twice
    return total;
  }

  // Whether particle i is pressed by a particle it is not bonded to (within the contact
  // distance), on the list of the last add_forces.
  bool touching(const VecArray<Dim, Scalar>& x, std::size_t i) const {
    if (i >= list_.num_queries()) return false;
    for (Offset k = list_.begin(i); k < list_.end(i); ++k)
      if ((x[i] - x[static_cast<std::size_t>(list_.indices[k])]).squaredNorm() < distance_ * distance_) return true;
    return false;
  }

  std::size_t active_pairs() const { return active_; }
  std::size_t candidate_pairs() const { return list_.num_pairs() / 2; }
  std::size_t rebuilds() const { return rebuilds_; }

  // Checkpoints (io/checkpoint.hpp): the Verlet list and where it was built, so that the pairs
  // are summed in the same order after a restart.
  template <class Archive>
  void checkpoint_state(Archive& a) {
    a.array(list_.offsets);
    a.array(list_.indices);
    a.array(list_.distances);
    a.array(built_at_);
    a.array(anchor_);
    a.array(stretch_);
    a.array(held_);
    a.value(cuts_at_build_);
    a.value(active_);
    a.value(rebuilds_);
  }

 private:
  bool needs_rebuild(const VecArray<Dim, Scalar>& x, const BondList<Dim, Scalar>& bonds) const {
    if (built_at_.size() != x.size() || bonds.num_cut() != cuts_at_build_) return true;
    if (friction_ > 0 && held_.size() != list_.num_pairs()) return true;  // friction set after the last build
    const Scalar limit2 = Scalar(0.25) * skin_ * skin_;
    bool moved = false;
    MPSFSI_OMP(parallel for schedule(static) reduction(|| : moved))
    for (std::int64_t i = 0; i < static_cast<std::int64_t>(x.size()); ++i)
      moved = moved || (x[static_cast<std::size_t>(i)] - built_at_[static_cast<std::size_t>(i)]).squaredNorm() > limit2;
    return moved;
  }

  void rebuild(const VecArray<Dim, Scalar>& x, const BondList<Dim, Scalar>& bonds) {
    if (!search_ || search_->radius() != distance_ + skin_) search_.emplace(distance_ + skin_);
    search_->build(x);
    search_->self_query(x, all_);
    if (friction_ > 0) std::swap(previous_, list_);  // the old rows, for carry_anchors()
    filter_neighbors(all_, [&](std::size_t i, Index j) { return !bonds.bonded(i, j); }, list_);
    if (friction_ > 0) carry_anchors();
    built_at_ = x;
    cuts_at_build_ = bonds.num_cut();
    ++rebuilds_;
  }

  // The Coulomb friction of the pair in `slot` (relative position r = x_i - x_j, unit normal e,
  // normal force `normal`): the tangential part s of r - anchor, s -> s mu f_n / (k |s|) when
  // k |s| exceeds mu f_n (the anchor follows, r - s), and -k s. A pair's two directions compute
  // the same numbers with opposite signs, so the forces are equal and opposite to the bit.
  vec_type friction_force(std::size_t slot, const vec_type& r, const vec_type& e, Scalar normal) {
    if (!held_[slot]) {
      anchor_[slot] = r;
      held_[slot] = 1;
    }
    return coulomb_friction(r, e, normal, friction_, stiffness_, anchor_[slot], stretch_[slot]);
  }

  // After a rebuild: each pair that was held keeps its anchor (looked up in its old row), every
  // other slot starts unheld.
  void carry_anchors() {
    const std::size_t slots = list_.num_pairs();
    new_anchor_.assign(slots, vec_type::Zero());
    new_stretch_.assign(slots, vec_type::Zero());
    new_held_.assign(slots, 0);
    const std::size_t rows = std::min(list_.num_queries(), previous_.num_queries());
    if (held_.size() == previous_.num_pairs())
      for (std::size_t i = 0; i < rows; ++i)
        for (Offset k = list_.begin(i); k < list_.end(i); ++k)
          for (Offset o = previous_.begin(i); o < previous_.end(i); ++o)
            if (previous_.indices[static_cast<std::size_t>(o)] == list_.indices[static_cast<std::size_t>(k)]) {
              const auto from = static_cast<std::size_t>(o), to = static_cast<std::size_t>(k);
              new_anchor_[to] = anchor_[from];
              new_stretch_[to] = stretch_[from];
              new_held_[to] = held_[from];
              break;
            }
    anchor_.swap(new_anchor_);
    stretch_.swap(new_stretch_);
    held_.swap(new_held_);
  }

  Scalar distance_ = 0, stiffness_ = 0, damping_ = 0, skin_ = 0, friction_ = 0;
  std::optional<CellListSearch<Dim, Scalar>> search_;
  BasicNeighborList<Scalar> all_, list_, previous_;
  VecArray<Dim, Scalar> built_at_;
  // Per slot of list_, with friction: the anchor, the last tangential stretch and whether the
  // pair has been in contact since its anchor was set.
  VecArray<Dim, Scalar> anchor_, stretch_, new_anchor_, new_stretch_;
  std::vector<std::uint8_t> held_, new_held_;
  std::size_t cuts_at_build_ = 0, active_ = 0, rebuilds_ = 0;
};

}  // namespace MPSFSI_ABI
}  // namespace mpsfsi
