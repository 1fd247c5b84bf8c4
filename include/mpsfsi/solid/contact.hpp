// SPDX-License-Identifier: BSD-3-Clause
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <optional>
#include <vector>

#include "mpsfsi/core/abi.hpp"
#include "mpsfsi/core/cell_list_search.hpp"
#include "mpsfsi/core/filter_neighbors.hpp"
#include "mpsfsi/core/neighbor_list.hpp"
#include "mpsfsi/core/parallel.hpp"
#include "mpsfsi/core/types.hpp"
#include "mpsfsi/solid/bonds.hpp"

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

// Frictionless penalty contact between particles that are not joined by an intact bond:
//   f_i = [k (d_c - r) - c (v_i - v_j) . e] e,  e = (x_i - x_j)/r,  for r < d_c,
// a linear spring that only pushes (energy k (d_c - r)^2 / 2 per pair) with an optional normal
// dashpot c = 2 zeta sqrt(k m/2) (zeta = SolidParameters::contact_damping_ratio, 0 by default)
// for impacts that should not bounce. Used at
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
    (void)n;
  }

  void add_forces(const VecArray<Dim, Scalar>& x, const VecArray<Dim, Scalar>& v, const BondList<Dim, Scalar>& bonds,
                  VecArray<Dim, Scalar>& force) {
    if (stiffness_ == 0) return;
    if (needs_rebuild(x, bonds)) rebuild(x, bonds);
    const auto n = static_cast<std::int64_t>(x.size());
    std::size_t active = 0;
    MPSFSI_OMP(parallel for schedule(static) reduction(+ : active))
    for (std::int64_t ii = 0; ii < n; ++ii) {
      const auto i = static_cast<std::size_t>(ii);
      vec_type f = vec_type::Zero();
      for (Offset k = list_.begin(i); k < list_.end(i); ++k) {
        const auto j = static_cast<std::size_t>(list_.indices[k]);
        const vec_type r = x[i] - x[j];
        const Scalar d2 = r.squaredNorm();
        if (d2 >= distance_ * distance_ || d2 == 0) continue;
        const Scalar d = std::sqrt(d2);
        const vec_type e = r / d;
        f += (stiffness_ * (distance_ - d) - damping_ * (v[i] - v[j]).dot(e)) * e;
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
    a.value(cuts_at_build_);
    a.value(active_);
    a.value(rebuilds_);
  }

 private:
  bool needs_rebuild(const VecArray<Dim, Scalar>& x, const BondList<Dim, Scalar>& bonds) const {
    if (built_at_.size() != x.size() || bonds.num_cut() != cuts_at_build_) return true;
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
    filter_neighbors(all_, [&](std::size_t i, Index j) { return !bonds.bonded(i, j); }, list_);
    built_at_ = x;
    cuts_at_build_ = bonds.num_cut();
    ++rebuilds_;
  }

  Scalar distance_ = 0, stiffness_ = 0, damping_ = 0, skin_ = 0;
  std::optional<CellListSearch<Dim, Scalar>> search_;
  BasicNeighborList<Scalar> all_, list_;
  VecArray<Dim, Scalar> built_at_;
  std::size_t cuts_at_build_ = 0, active_ = 0, rebuilds_ = 0;
};

}  // namespace MPSFSI_ABI
}  // namespace mpsfsi
