// SPDX-License-Identifier: BSD-3-Clause
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "mpsfsi/core/abi.hpp"
#include "mpsfsi/core/error.hpp"
#include "mpsfsi/core/parallel.hpp"
#include "mpsfsi/core/types.hpp"
#include "mpsfsi/solid/coulomb_friction.hpp"

namespace mpsfsi {
inline namespace MPSFSI_ABI {

// A rigid convex body that moves as the program prescribes (a translation at a velocity it sets
// between steps) and that the solid's particles touch: a structure, a moving wall, a floor
// (docs/theory.md, section 3.5). Its shape is the intersection of half-spaces, each given by a
// point on its face and the face's outward normal. A particle at x lies outside at
//   g(x) = max_f n_f . (x - p_f - u),   u the body's displacement since it was made,
// the distance to the nearest face where that face is nearest (near an edge or corner g is
// smaller than the true distance: the faces are extended, the corners not rounded). A particle
// with g < d, d half the contact distance of two particles, is pushed off the face f* that gives g:
//   f = [k (d - g) - c (v - V) . n] n + f_t,   n = n_f*,   V the body's velocity,
// the particle pairs' spring k and dashpot c (PenaltyContact), so that a body's surface, half a
// spacing beyond its outer particles, meets the face as it meets another body's surface. f_t is
// PenaltyContact's Coulomb friction: a tangential spring k from the point, fixed on the body,
// where the particle first touched, capped at mu times the normal force (mu: the body's own, or
// SolidParameters::contact_friction). load() is the sum of the reactions, the force the
// particles exert on the body. ElasticSolver::add_obstacle gives the body to a solver, which moves
// it and adds its forces at every step.
template <int Dim, class Scalar = double>
class RigidObstacle {
 public:
  using vec_type = Vec<Dim, Scalar>;
  struct Face {
    vec_type point;   // a point on the face
    vec_type normal;  // pointing out of the body (normalised on construction)
  };

  // Throws InvalidInput for no faces, a non-finite point or normal, or a zero normal.
  explicit RigidObstacle(std::vector<Face> faces) : faces_(std::move(faces)) {
    if (faces_.empty()) detail::throw_invalid("RigidObstacle", "the obstacle has no faces");
    for (std::size_t f = 0; f < faces_.size(); ++f) {
      auto& face = faces_[f];
      if (!face.point.allFinite() || !face.normal.allFinite() || !(face.normal.norm() > 0))
        detail::throw_invalid("RigidObstacle", "face " + std::to_string(f) +
                                                   " needs a finite point and a finite non-zero normal");
      face.normal.normalize();
    }
  }

  // Everything on the side of the plane through `point` opposite to `outward_normal` (a floor, a
  // wall, a slope that reaches beyond the particles).
  static RigidObstacle half_space(const vec_type& point, const vec_type& outward_normal) {
    return RigidObstacle({Face{point, outward_normal}});
  }

  // The convex polygon with the given corners in counter-clockwise order: in 2D in the (x, y)
  // plane; in 3D in the (x, z) plane, swept along y without end (a plate across a channel).
  // Throws InvalidInput for fewer than three corners, non-finite ones, a repeated corner, or
  // corners that are not convex and counter-clockwise.
  static RigidObstacle polygon(const std::vector<Vec<2, Scalar>>& corners) {
    const std::size_t m = corners.size();
    if (m < 3) detail::throw_invalid("RigidObstacle::polygon", "a polygon needs at least three corners");
    Scalar size = 0;
    for (const auto& c : corners) {
      if (!c.allFinite()) detail::throw_invalid("RigidObstacle::polygon", "a corner is not finite");
      size = std::max(size, (c - corners[0]).norm());
    }
    std::vector<Face> faces;
    for (std::size_t k = 0; k < m; ++k) {
      const Vec<2, Scalar>& a = corners[k];
      const Vec<2, Scalar> edge = corners[(k + 1) % m] - a;
      if (!(edge.norm() > 1e-12 * size))
        detail::throw_invalid("RigidObstacle::polygon", "corners " + std::to_string(k) + " and " +
                                                            std::to_string((k + 1) % m) + " coincide");
      const Vec<2, Scalar> out(edge[1], -edge[0]);  // outward for counter-clockwise corners
      for (std::size_t j = 0; j < m; ++j)
        if (out.normalized().dot(corners[j] - a) > 1e-9 * size)
          detail::throw_invalid("RigidObstacle::polygon", "the corners are not convex and counter-clockwise (corner " +
                                                              std::to_string(j) + " lies outside edge " +
                                                              std::to_string(k) + ")");
      faces.push_back(Face{in_plane(a), in_plane(out)});
    }
    return RigidObstacle(std::move(faces));
  }

  // The velocity from now on (m/s); the solver moves the body by it at every step.
  void set_velocity(const vec_type& v) {
    if (!v.allFinite()) detail::throw_invalid("RigidObstacle::set_velocity", "the velocity is not finite");
    velocity_ = v;
  }
  const vec_type& velocity() const { return velocity_; }
  // How far the body has moved since it was made.
  const vec_type& displacement() const { return displacement_; }
  const std::vector<Face>& faces() const { return faces_; }

  // Coulomb friction between this body and the particles, instead of
  // SolidParameters::contact_friction. Throws InvalidInput unless mu is finite and >= 0.
  void set_friction(Scalar mu) {
    if (!(mu >= 0) || !std::isfinite(mu))
      detail::throw_invalid("RigidObstacle::set_friction", "the friction coefficient must be finite and >= 0");
    friction_ = mu;
  }
  // The coefficient in use (negative before the body is given to a solver without its own).
  Scalar friction() const { return friction_; }

  // g(x) above: positive outside the body, negative inside.
  Scalar distance(const vec_type& x) const { return nearest_face(x).second; }

  // The force the particles exert on the body at the last force evaluation (N; per unit thickness
  // in 2D), and how many particles touched it then.
  const vec_type& load() const { return load_; }
  std::size_t touching_particles() const { return touching_; }

  // --- Used by ElasticSolver ---

  // The contact law of the solver's particles: the distance d at which a particle touches, the
  // spring, the dashpot, and the solver's friction coefficient when the body has none of its own.
  void attach(std::size_t n, Scalar distance, Scalar stiffness, Scalar damping, Scalar solver_friction) {
    distance_ = distance;
    stiffness_ = stiffness;
    damping_ = damping;
    if (friction_ < 0) friction_ = solver_friction;
    anchor_.assign(n, vec_type::Zero());
    stretch_.assign(n, vec_type::Zero());
    held_.assign(n, 0);
  }

  void move(Scalar dt) { displacement_ += dt * velocity_; }

  // Adds the contact forces on the particles at x moving at v to `force`, and sets load().
  void add_forces(const VecArray<Dim, Scalar>& x, const VecArray<Dim, Scalar>& v, VecArray<Dim, Scalar>& force) {
    const auto n = static_cast<std::int64_t>(x.size());
    const bool frictional = friction_ > 0;
    Scalar load0 = 0, load1 = 0, load2 = 0;
    std::size_t touching = 0;
    MPSFSI_OMP(parallel for schedule(static) reduction(+ : load0, load1, load2, touching))
    for (std::int64_t ii = 0; ii < n; ++ii) {
      const auto i = static_cast<std::size_t>(ii);
      const auto [face, gap] = nearest_face(x[i]);
      if (gap >= distance_) {
        if (frictional && gap >= release_distance()) held_[i] = 0;
        continue;
      }
      const vec_type& e = faces_[face].normal;
      const Scalar normal = stiffness_ * (distance_ - gap) - damping_ * (v[i] - velocity_).dot(e);
      vec_type f = normal * e;
      if (frictional) f += friction_force(i, vec_type(x[i] - displacement_), e, normal);
      force[i] += f;
      load0 -= f[0];
      load1 -= f[1];
      if constexpr (Dim == 3) load2 -= f[2];
      ++touching;
    }
    load_[0] = load0;
    load_[1] = load1;
    if constexpr (Dim == 3) load_[2] = load2;
    touching_ = touching;
  }

  bool touching(const vec_type& x) const { return distance(x) < distance_; }

  // The springs' energy: k (d - g)^2 / 2 per touching particle and k |s|^2 / 2 per sticking one.
  Scalar energy(const VecArray<Dim, Scalar>& x) const {
    Scalar total = 0;
    for (std::size_t i = 0; i < x.size(); ++i) {
      const Scalar gap = distance(x[i]);
      if (gap >= distance_) continue;
      total += Scalar(0.5) * stiffness_ * (distance_ - gap) * (distance_ - gap);
      if (i < held_.size() && held_[i]) total += Scalar(0.5) * stiffness_ * stretch_[i].squaredNorm();
    }
    return total;
  }

  // Checkpoints and iterative coupling: the motion, the friction anchors and the last load.
  template <class Archive>
  void checkpoint_state(Archive& a) {
    a.value(displacement_);
    a.value(velocity_);
    a.array(anchor_);
    a.array(stretch_);
    a.array(held_);
    a.value(load_);
    a.value(touching_);
  }
  std::size_t checkpoint_particle_count() const { return held_.size(); }

 private:
  static vec_type in_plane(const Vec<2, Scalar>& p) {
    if constexpr (Dim == 2)
      return p;
    else
      return vec_type(p[0], 0, p[1]);
  }

  // A particle keeps its friction anchor until it is this far from the body, so that one that
  // leaves the face for a moment as the body rings (by much less than a spacing) lands where it
  // stuck, instead of starting its tangential spring again from nothing.
  Scalar release_distance() const { return Scalar(1.5) * distance_; }

  std::pair<std::size_t, Scalar> nearest_face(const vec_type& x) const {
    std::size_t best = 0;
    Scalar gap = -std::numeric_limits<Scalar>::infinity();
    for (std::size_t f = 0; f < faces_.size(); ++f) {
      const Scalar g = faces_[f].normal.dot(x - faces_[f].point - displacement_);
      if (g > gap) {
        gap = g;
        best = f;
      }
    }
    return {best, gap};
  }

  vec_type friction_force(std::size_t i, const vec_type& r, const vec_type& e, Scalar normal) {
    if (!held_[i]) {
      anchor_[i] = r;
      held_[i] = 1;
    }
    return coulomb_friction(r, e, normal, friction_, stiffness_, anchor_[i], stretch_[i]);
  }

  std::vector<Face> faces_;
  vec_type velocity_ = vec_type::Zero(), displacement_ = vec_type::Zero(), load_ = vec_type::Zero();
  Scalar distance_ = 0, stiffness_ = 0, damping_ = 0, friction_ = -1;
  // Per particle, with friction: the anchor (relative to the body), the last tangential stretch
  // and whether the particle has touched since its anchor was set.
  VecArray<Dim, Scalar> anchor_, stretch_;
  std::vector<std::uint8_t> held_;
  std::size_t touching_ = 0;
};

// The rigid bodies a solver's particles touch: adds them with the solver's contact law, moves
// them, adds their forces, and holds them in checkpoints (ElasticSolver's obstacles).
template <int Dim, class Scalar = double>
class RigidObstacles {
 public:
  using obstacle_type = RigidObstacle<Dim, Scalar>;
  using vec_type = typename obstacle_type::vec_type;

  // The body with the contact law of n particles (RigidObstacle::attach); returns its index.
  std::size_t add(obstacle_type obstacle, std::size_t n, Scalar distance, Scalar stiffness, Scalar damping,
                  Scalar solver_friction) {
    obstacle.attach(n, distance, stiffness, damping, solver_friction);
    bodies_.push_back(std::move(obstacle));
    return bodies_.size() - 1;
  }
  std::size_t size() const { return bodies_.size(); }
  // Body k; throws InvalidInput if there is none.
  obstacle_type& at(std::size_t k) {
    check(k);
    return bodies_[k];
  }
  const obstacle_type& at(std::size_t k) const {
    check(k);
    return bodies_[k];
  }

  void move(Scalar dt) {
    for (auto& body : bodies_) body.move(dt);
  }
  void add_forces(const VecArray<Dim, Scalar>& x, const VecArray<Dim, Scalar>& v, VecArray<Dim, Scalar>& force) {
    for (auto& body : bodies_) body.add_forces(x, v, force);
  }
  bool touching(const vec_type& x) const {
    return std::any_of(bodies_.begin(), bodies_.end(), [&](const auto& body) { return body.touching(x); });
  }
  Scalar energy(const VecArray<Dim, Scalar>& x) const {
    Scalar total = 0;
    for (const auto& body : bodies_) total += body.energy(x);
    return total;
  }

  // The number of bodies, then each body's state; reading throws InvalidInput if the checkpoint
  // holds a different number of bodies than were added.
  template <class Archive>
  void checkpoint_state(Archive& a) {
    std::uint64_t count = bodies_.size();
    a.value(count);  // overwritten when reading
    if (count != bodies_.size())
      detail::throw_invalid("RigidObstacles", "the checkpoint has " + std::to_string(count) +
                                                  " obstacles; this solver has " + std::to_string(bodies_.size()));
    for (auto& body : bodies_) body.checkpoint_state(a);
  }
  // Whether every body's per-particle state is sized for n particles (after reading a checkpoint).
  bool sized_for(std::size_t n) const {
    return std::all_of(bodies_.begin(), bodies_.end(),
                       [n](const auto& body) { return body.checkpoint_particle_count() == n; });
  }

 private:
  void check(std::size_t k) const {
    if (k >= bodies_.size())
      detail::throw_invalid("RigidObstacles::at", "obstacle " + std::to_string(k) + " out of range (" +
                                                      std::to_string(bodies_.size()) + ")");
  }

  std::vector<obstacle_type> bodies_;
};

}  // namespace MPSFSI_ABI
}  // namespace mpsfsi
