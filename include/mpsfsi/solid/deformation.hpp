// SPDX-License-Identifier: BSD-3-Clause
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include <Eigen/Eigenvalues>

#include "mpsfsi/core/abi.hpp"
#include "mpsfsi/core/parallel.hpp"
#include "mpsfsi/core/types.hpp"
#include "mpsfsi/solid/bonds.hpp"
#include "mpsfsi/solid/solid_parameters.hpp"

namespace mpsfsi {
inline namespace MPSFSI_ABI {

// What a stress model needs to know about the material and the discretisation.
template <int Dim, class Scalar = double>
struct SolidModelContext {
  LameConstants<Scalar> lame;
  Scalar density = 0;
  Scalar l0 = 0;
  Scalar volume = 0;      // l0^d per particle (per unit thickness in 2D)
  Scalar n0 = 0;          // number density of a full lattice neighbourhood (eq 12)
  Scalar lap_lambda = 0;  // Laplacian constant of the lattice (Koshizuka & Oka 1996)
};

// Second-order corrected deformation gradient. Around each particle i the current bond vectors
// are fitted, in the weighted least-squares sense over i's intact bonds (weights beta_ij), by a
// linear plus quadratic function of the reference bond vectors:
//   r_ij ~ A_i phi(r0_ij),   phi(r) = [r, q(r)/l0],  q(r) = the d(d+1)/2 products r_a r_b (a <= b),
// halved on the diagonal. F_i is the linear part of A_i. The fit is the corrected gradient of
// Khayyer & Gotoh (2011) raised by one order: a linear-only fit is exact for affine motion but, at
// a free surface where the neighbourhood is one-sided, it reads the bending strain about 0.8 l0
// inside the particle (the quadratic part of the field leaks into the gradient). The quadratic
// terms remove that error (oscillating plate at H/l0 = 10: period error 4.0 % with the linear fit,
// 2.8 % with the quadratic one, the rest from the clamp; docs/theory.md, section 3.3).
// A_i = [I 0] + sum_j (r_ij - r0_ij) g_ij^T with g_ij = beta_ij M_i^+ phi(r0_ij) and
// M_i = sum_j beta_ij phi phi^T. A particle whose neighbourhood cutting has thinned (in some
// direction less than a quarter of the weight of its intact neighbourhood's strongest) uses the
// linear fit with those directions' weight raised to that quarter (kWeakDirectionFloor): it
// reads them softly, and the part of F they do not set turns with the bonded directions
// (objective()), so that a rigid rotation reads as one. A chip with no bond keeps F = I (it
// carries no stress).
template <int Dim, class Scalar = double>
class DeformationFit {
 public:
  static constexpr int quad = Dim * (Dim + 1) / 2;
  static constexpr int width = Dim + quad;
  using vec_type = Vec<Dim, Scalar>;
  using mat_type = Mat<Dim, Scalar>;
  using basis_type = Eigen::Matrix<Scalar, width, 1>;
  using quad_type = Eigen::Matrix<Scalar, quad, 1>;
  using affine_type = Eigen::Matrix<Scalar, Dim, width>;
  using moment_type = Eigen::Matrix<Scalar, width, width>;

  // Fit coefficients of every bond, for the bonds as they are now, which become the reference
  // neighbourhoods: each particle keeps the largest eigenvalue of its linear moment matrix (a full
  // neighbourhood's is n0/d on a lattice) to weigh its fit against once bonds are cut (rebuild).
  void build(const BondList<Dim, Scalar>& bonds, Scalar l0) {
    inv_l0_ = 1 / l0;
    const std::size_t n = bonds.num_particles();
    coeff_.resize(bonds.num_bonds());
    inverse_moment_.resize(n);
    gradient_sum_.resize(n);
    reference_moment_.resize(n);
    resize_soft_reading(n);
    MPSFSI_OMP(parallel for schedule(dynamic, 64))
    for (std::int64_t ii = 0; ii < static_cast<std::int64_t>(n); ++ii) {
      const auto i = static_cast<std::size_t>(ii);
      reference_moment_[i] = linear_moment(bonds, i).eigenvalues().maxCoeff();
      rebuild(bonds, i);
    }
  }

  // Refits particle i only (after some of its bonds were cut).
  void rebuild(const BondList<Dim, Scalar>& bonds, std::size_t i) {
    Eigen::Matrix<Scalar, width, width> m = Eigen::Matrix<Scalar, width, width>::Zero();
    for (Offset b = bonds.begin(i); b < bonds.end(i); ++b) {
      const basis_type p = basis(bonds.r0(b));
      m.noalias() += bonds.beta(b) * p * p.transpose();
    }
    // The quadratic fit needs bonds in enough directions and with enough weight. Next to a crack
    // or at a fragment's corner a particle may not have them; it then falls back to the linear
    // (Khayyer-Gotoh) fit with its weakly resolved directions read softly (kWeakDirectionFloor).
    const auto linear = linear_moment(bonds, i);
    set_soft_reading(linear, i);
    Eigen::Matrix<Scalar, width, width> pinv = Eigen::Matrix<Scalar, width, width>::Zero();
    if (linear.eigenvalues().minCoeff() < kWeakDirectionFloor * reference_moment_[i] ||
        !pseudo_inverse<width>(m, pinv, kQuadraticConditionLimit)) {
      vec_type inverse;
      for (int k = 0; k < Dim; ++k)
        inverse[k] = 1 / std::max(linear.eigenvalues()[k], kWeakDirectionFloor * reference_moment_[i]);
      pinv.setZero();
      pinv.template topLeftCorner<Dim, Dim>() =
          linear.eigenvectors() * inverse.asDiagonal() * linear.eigenvectors().transpose();
    }
    // Symmetric to the bit, so that the force loop, which reads one triangle of it, and the
    // coefficients below use the same matrix.
    pinv = (Scalar(0.5) * (pinv + pinv.transpose())).eval();
    inverse_moment_[i] = pinv;
    vec_type sum = vec_type::Zero();
    for (Offset b = bonds.begin(i); b < bonds.end(i); ++b) {
      coeff_[static_cast<std::size_t>(b)] = bonds.beta(b) * (pinv * basis(bonds.r0(b)));
      sum += coeff_[static_cast<std::size_t>(b)].template head<Dim>();
    }
    gradient_sum_[i] = sum;
  }

  // The fitted map A_i at positions x.
  affine_type affine(const VecArray<Dim, Scalar>& x, const BondList<Dim, Scalar>& bonds, std::size_t i) const {
    affine_type a = affine_type::Zero();
    const vec_type xi = x[i];
    const auto& nb = bonds.neighbors();
    const auto& r0 = bonds.reference_vectors();
    for (Offset b = bonds.begin(i); b < bonds.end(i); ++b) {
      const auto k = static_cast<std::size_t>(b);
      a.noalias() += (x[static_cast<std::size_t>(nb[k])] - xi - r0[k]) * coeff_[k].transpose();
    }
    a.template leftCols<Dim>() += mat_type::Identity();
    if (reads_softly(i)) a.template leftCols<Dim>() = objective(a.template leftCols<Dim>(), i);
    return a;
  }

  // F_i, the linear part of A_i (the same sums as affine(), without the quadratic columns).
  mat_type gradient(const VecArray<Dim, Scalar>& x, const BondList<Dim, Scalar>& bonds, std::size_t i) const {
    mat_type f = mat_type::Zero();
    const vec_type xi = x[i];
    const auto& nb = bonds.neighbors();
    const auto& r0 = bonds.reference_vectors();
    for (Offset b = bonds.begin(i); b < bonds.end(i); ++b) {
      const auto k = static_cast<std::size_t>(b);
      f.noalias() += (x[static_cast<std::size_t>(nb[k])] - xi - r0[k]) * coeff_[k].template head<Dim>().transpose();
    }
    return objective(f + mat_type::Identity(), i);
  }

  // Deformation gradient of the fitted map a = A_i at reference offset r from particle i: the
  // derivative of A_i phi(r), F(r) = A_lin + A_quad dq(r)/dr / l0, linear in r (F(0) = A_lin).
  // The failure criterion uses it to read the stress at the body's surface, l0/2 outside the
  // outermost particles.
  mat_type gradient_at(const affine_type& a, const vec_type& r) const {
    Eigen::Matrix<Scalar, quad, Dim> dq = Eigen::Matrix<Scalar, quad, Dim>::Zero();
    int k = 0;
    for (int p = 0; p < Dim; ++p)
      for (int q = p; q < Dim; ++q, ++k) {
        // d/dr of (p == q ? r_p^2 / 2 : r_p r_q), divided by l0
        dq(k, p) += r[q] * inv_l0_;
        if (p != q) dq(k, q) += r[p] * inv_l0_;
      }
    return a.template leftCols<Dim>() + a.template rightCols<quad>() * dq;
  }

  // q(r)/l0: the quadratic part of phi.
  quad_type quadratic(const vec_type& r) const {
    quad_type q;
    int k = 0;
    for (int a = 0; a < Dim; ++a)
      for (int b = a; b < Dim; ++b) q[k++] = (a == b ? Scalar(0.5) : Scalar(1)) * r[a] * r[b] * inv_l0_;
    return q;
  }

  basis_type basis(const vec_type& r) const {
    basis_type p;
    p << r, quadratic(r);
    return p;
  }

  // g_ij restricted to the gradient (the first d entries), and sum_j g_ij per particle.
  Eigen::Ref<const vec_type> gradient_coefficient(Offset b) const {
    return coeff_[static_cast<std::size_t>(b)].template head<Dim>();
  }
  // Checkpoints (io/checkpoint.hpp): the fits as they are after the cuts so far, and the intact
  // neighbourhoods' moments the weak-direction floor refers to.
  template <class Archive>
  void checkpoint_state(Archive& a) {
    a.value(inv_l0_);
    a.array(reference_moment_);
    a.array(coeff_);
    a.array(inverse_moment_);
    a.array(gradient_sum_);
  }

  const std::vector<basis_type>& coefficients() const { return coeff_; }
  // M_i^+ as used above (symmetric): g_ij = beta_ij M_i^+ phi(r0_ij) for every bond of i.
  const moment_type& inverse_moment(std::size_t i) const { return inverse_moment_[i]; }
  const vec_type& gradient_sum(std::size_t i) const { return gradient_sum_[i]; }

  // Whether particle i has a direction that no intact bond resolves at all.
  bool has_free_direction(std::size_t i) const { return resolved_[i] > 0 && resolved_[i] < Dim; }
  // Whether particle i reads a direction softly (below kWeakDirectionFloor, or without bonds):
  // then objective() turns its F.
  bool reads_softly(std::size_t i) const { return turn_[i] != kNoTurn; }
  // Its linear moment matrix M_i = sum_j beta_ij r0_ij r0_ij^T, as the floor last saw it.
  mat_type moment_matrix(std::size_t i) const {
    return moment_vectors_[i] * moment_values_[i].asDiagonal() * moment_vectors_[i].transpose();
  }

  // The fitted F of a particle that reads directions softly, made objective (docs/theory.md,
  // section 3.3, "The turned floor"). With the floored inverse M_f^-1 the fit is
  //   F = F_b + S,  F_b = sum_j beta_ij r_ij r0_ij^T M_f^-1,  S = I - M M_f^-1,
  // S being the share of each weak direction that the bonds do not set (zero where the weight is
  // above the floor, one where no bond is). S does not turn with the body: a rigid rotation Q
  // gives F_b = Q (I - S) and F = Q + (I - Q) S, a shear of about theta s / 2 at every thinned
  // particle. The turned fit is F_obj = F_b + Q(F_b) S, with Q the rotation of the particle's
  // directions as its bonds see them: in 2D the rotation of F_b's polar decomposition (which no
  // choice of axes enters, so mirror images turn as mirror images); for a line of bonds in 3D the
  // rotation taking the line a onto F_b a; in 3D with one weak direction n, Q n is the unit normal
  // of the turned strong plane; with two or three, Q takes the frame (a, b, a x b) of the strongest
  // and second directions onto the Gram-Schmidt frame of (F_b a, F_b b). F_obj = Q under any
  // rigid rotation.
  mat_type objective(const mat_type& f, std::size_t i) const { return turned(f, i, nullptr, nullptr); }

  // What the turn adds to the stress conjugate to the fit: for a first Piola-Kirchhoff-like
  // matrix P conjugate to F_obj, the gradient of psi(F_obj(F_b)) with respect to F_b is P + dP with
  // dP = (dQ S / dF_b)^T : P. The force loop adds it, so that the forces stay the exact negative
  // gradient of the energy. Zero for a particle that does not read softly.
  mat_type objective_stress_term(const mat_type& f, const mat_type& p, std::size_t i) const {
    mat_type dp = mat_type::Zero();
    turned(f, i, &p, &dp);
    return dp;
  }

  // Recomputes which directions each particle's intact bonds resolve (after a checkpoint is read:
  // the fit's arrays are stored, these follow from the bonds).
  void restore_resolved_directions(const BondList<Dim, Scalar>& bonds) {
    const std::size_t n = bonds.num_particles();
    resize_soft_reading(n);
    MPSFSI_OMP(parallel for schedule(dynamic, 64))
    for (std::int64_t ii = 0; ii < static_cast<std::int64_t>(n); ++ii) {
      const auto i = static_cast<std::size_t>(ii);
      set_soft_reading(linear_moment(bonds, i), i);
    }
  }

 private:
  // Smallest eigenvalue / largest accepted for the quadratic fit (at re = 2.1 l0 a full lattice
  // neighbourhood has 0.2, a flat free surface's 8 bonds 0.0033, a corner's 5 bonds 0.0044).
  static constexpr Scalar kQuadraticConditionLimit = Scalar(1e-3);

  // The least weight, as a fraction of the strongest direction of the particle's intact
  // neighbourhood (reference_moment_), with which a direction is read at face value. A least-squares
  // fit normalises the weights away: a particle left by cutting with a strong bond and a long weak
  // one (w(2 l0) is 1/22 of w(l0)) reads the weak bond's stretch as fully as the strong one's.
  // Beside an opening crack such a bond spans the gap, stretched by tens of per cent, and the refit
  // particle jumps from sigma_f to 100 times it, which puts the energy of the whole beam into a few
  // particles in one step (without the floor the l0 = 1 mm bending beam shatters;
  // docs/validation/fracture.md). Below the floor the moment matrix's eigenvalue is raised to it, so
  // such a direction counts in proportion to the weight it has: no bond's coefficient is more than
  // 1/floor times its value in the intact neighbourhood. Every particle of an intact lattice is
  // above it (the weakest direction anywhere, at a corner, is 0.35 of a full neighbourhood's in 2D
  // and 0.29 in 3D at re = 2.1 l0, and more of the corner's own strongest); directions without any
  // bond have none to count and turn with the bonded ones (objective()).
  static constexpr Scalar kWeakDirectionFloor = Scalar(0.25);

  // How particle i's F turns (objective()): kTurnWithAxis in 2D (the polar rotation) and for a
  // line of bonds in 3D, kTurnWithPlane when one direction of three is weak, kTurnWithFrame when
  // two or three are.
  enum Turn : std::uint8_t { kNoTurn, kTurnWithAxis, kTurnWithPlane, kTurnWithFrame };

  void resize_soft_reading(std::size_t n) {
    resolved_.assign(n, Dim);
    turn_.assign(n, kNoTurn);
    moment_values_.assign(n, vec_type::Zero());
    moment_vectors_.assign(n, mat_type::Identity());
  }

  // Particle i's linear moment (its eigen-decomposition), the number of directions its intact
  // bonds resolve (its rank) and how its F turns.
  void set_soft_reading(const Eigen::SelfAdjointEigenSolver<mat_type>& linear, std::size_t i) {
    const auto& values = linear.eigenvalues();  // ascending
    moment_values_[i] = values;
    moment_vectors_[i] = linear.eigenvectors();
    // Zero up to the round-off of sums of order reference_moment_ (a cut bond leaves nothing).
    const Scalar zero = Scalar(1e-10) * reference_moment_[i];
    const Scalar floor = kWeakDirectionFloor * reference_moment_[i];
    int rank = 0, weak = 0;
    for (int k = 0; k < Dim; ++k) {
      rank += values[k] > zero ? 1 : 0;
      weak += values[k] < floor ? 1 : 0;
    }
    resolved_[i] = static_cast<std::uint8_t>(rank);
    if (rank == 0 || weak == 0) turn_[i] = kNoTurn;
    else if (Dim == 2 || rank == 1) turn_[i] = kTurnWithAxis;
    else if (weak == 1) turn_[i] = kTurnWithPlane;
    else turn_[i] = kTurnWithFrame;
  }

  // The unset share of each eigen-direction, s_k = 1 - lambda_k / max(lambda_k, floor): S's
  // eigenvalues (S = I - M M_f^-1).
  vec_type soft_shares(std::size_t i) const {
    const Scalar floor = kWeakDirectionFloor * reference_moment_[i];
    vec_type s;
    for (int k = 0; k < Dim; ++k) {
      const Scalar value = std::max(moment_values_[i][k], Scalar(0));
      s[k] = value < floor ? 1 - value / floor : Scalar(0);
    }
    return s;
  }

  // F_obj = F_b + Q S (objective()) and, if p is given, dp = the adjoint of F_b -> Q(F_b) S applied
  // to p (objective_stress_term()). The derivatives: in 2D d(Q S) = d theta J Q S (J the quarter
  // turn), so dp = <p, J Q S> d theta / dF_b; for a line of bonds in 3D, p a is along Q a and the
  // rest of p meets no g_ij, so dp = 0 on the bonds' span; the plane and frame cases differentiate
  // the normalised cross product and the Gram-Schmidt steps (docs/theory.md, section 3.3).
  mat_type turned(const mat_type& f, std::size_t i, const mat_type* p, mat_type* dp) const {
    if (turn_[i] == kNoTurn) return f;
    const mat_type& v = moment_vectors_[i];
    const vec_type s = soft_shares(i);
    const mat_type soft = v * s.asDiagonal() * v.transpose();
    const mat_type bonded = f - soft;
    if constexpr (Dim == 2) {
      // The rotation of F_b's polar decomposition, by theta = atan2(F21 - F12, F11 + F22).
      const Scalar x = bonded(0, 0) + bonded(1, 1), y = bonded(1, 0) - bonded(0, 1);
      const Scalar r2 = x * x + y * y;
      if (!(r2 > 0)) return f;
      const Scalar r = std::sqrt(r2);
      mat_type q, quarter;
      q << x / r, -y / r, y / r, x / r;
      quarter << 0, -1, 1, 0;
      const mat_type turned_soft = q * soft;
      if (p) {
        mat_type dtheta;  // d theta / d F_b
        dtheta << -y, -x, x, -y;
        *dp = (p->cwiseProduct(quarter * turned_soft).sum() / r2) * dtheta;
      }
      return bonded + turned_soft;
    } else {
      if (turn_[i] == kTurnWithAxis) {
        // A line of bonds: the rest of p meets no g_ij, and p a is along e1, so dp = 0 on the span.
        const vec_type a = v.col(Dim - 1);
        const vec_type u = bonded * a;
        const Scalar length = u.norm();
        if (!(length > 0)) return f;
        return bonded + rotation_onto(a, u / length) * soft;
      }
      if (turn_[i] == kTurnWithPlane) {
        const vec_type n = v.col(0), t1 = v.col(1), t2 = n.cross(t1);  // t1 x t2 = n
        const vec_type v1 = bonded * t1, v2 = bonded * t2, normal = v1.cross(v2);
        const Scalar area = normal.norm();
        if (!(area > 0)) return f;
        const vec_type q = normal / area;
        if (p) {
          // d(p_n . q) = pi . dN with p_n = s_n p n, pi = (I - q q^T) p_n / |N|, N = v1 x v2.
          const vec_type pull = s[0] * (*p * n);
          const vec_type pi = (pull - q * q.dot(pull)) / area;
          *dp = v2.cross(pi) * t1.transpose() + pi.cross(v1) * t2.transpose();
        }
        return bonded + s[0] * q * n.transpose();
      }
      const vec_type a = v.col(2), b = v.col(1), c = a.cross(b);
      const vec_type x = bonded * a, y = bonded * b;
      const Scalar x_length = x.norm();
      if (!(x_length > 0)) return f;
      const vec_type e1 = x / x_length;
      const vec_type w = y - e1 * e1.dot(y);
      const Scalar w_length = w.norm();
      if (!(w_length > 0)) return f;
      const vec_type e2 = w / w_length, e3 = e1.cross(e2);
      if (p) {
        // phi = p1 . e1 + p2 . e2 + p3 . (e1 x e2), p_k = s_k p v_k, differentiated through
        // e2 = w/|w|, w = y - (e1 . y) e1 and e1 = x/|x|.
        const vec_type p1 = s[2] * (*p * a), p2 = s[1] * (*p * b), p3 = s[0] * (*p * c);
        const vec_type g1 = p1 + e2.cross(p3), g2 = p2 + p3.cross(e1);
        const vec_type h = (g2 - e2 * e2.dot(g2)) / w_length;
        const vec_type k0 = g1 - e1.dot(h) * y - e1.dot(y) * h;
        const vec_type k = (k0 - e1 * e1.dot(k0)) / x_length;
        *dp = k * a.transpose() + (h - e1 * e1.dot(h)) * b.transpose();
      }
      return bonded + s[2] * e1 * a.transpose() + s[1] * e2 * b.transpose() + s[0] * e3 * c.transpose();
    }
  }

  // The least rotation taking unit vector a to unit vector b (3D): about a x b, or through pi
  // about a direction normal to a when b = -a.
  static mat_type rotation_onto(const vec_type& a, const vec_type& b) {
    const Scalar c = a.dot(b);
    if (c < Scalar(-1) + Scalar(1e-12)) {
      const vec_type p = a.unitOrthogonal();
      return Scalar(2) * p * p.transpose() - mat_type::Identity();
    }
    const vec_type v = a.cross(b);
    mat_type k;
    k << 0, -v[2], v[1], v[2], 0, -v[0], -v[1], v[0], 0;
    return mat_type::Identity() + k + k * k / (1 + c);  // Rodrigues' formula
  }

  // Eigen-decomposition of particle i's linear moment matrix sum_j beta_ij r0_ij r0_ij^T.
  static Eigen::SelfAdjointEigenSolver<mat_type> linear_moment(const BondList<Dim, Scalar>& bonds, std::size_t i) {
    mat_type m = mat_type::Zero();
    for (Offset b = bonds.begin(i); b < bonds.end(i); ++b) m.noalias() += bonds.beta(b) * bonds.r0(b) * bonds.r0(b).transpose();
    return Eigen::SelfAdjointEigenSolver<mat_type>(m);
  }

  // Pseudo-inverse of a symmetric positive semi-definite matrix, dropping eigenvalues below
  // 1e-8 of the largest. Returns false (and leaves `out` unspecified) if the smallest eigenvalue
  // is below condition_limit times the largest.
  template <int N>
  static bool pseudo_inverse(const Eigen::Matrix<Scalar, N, N>& m, Eigen::Matrix<Scalar, N, N>& out, Scalar condition_limit) {
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix<Scalar, N, N>> eig(m);
    const auto& values = eig.eigenvalues();
    const Scalar largest = values.cwiseAbs().maxCoeff();
    if (!(largest > 0)) {
      out.setZero();
      return condition_limit == 0;
    }
    if (values.minCoeff() < condition_limit * largest) return false;
    Eigen::Matrix<Scalar, N, 1> inverse = Eigen::Matrix<Scalar, N, 1>::Zero();
    for (int k = 0; k < N; ++k)
      if (values[k] > Scalar(1e-8) * largest) inverse[k] = Scalar(1) / values[k];
    out = eig.eigenvectors() * inverse.asDiagonal() * eig.eigenvectors().transpose();
    return true;
  }

  Scalar inv_l0_ = 1;
  std::vector<Scalar> reference_moment_;
  std::vector<basis_type> coeff_;
  std::vector<moment_type, Eigen::aligned_allocator<moment_type>> inverse_moment_;
  VecArray<Dim, Scalar> gradient_sum_;
  std::vector<std::uint8_t> resolved_;  // directions the intact bonds resolve, 0 to Dim
  std::vector<Turn> turn_;
  VecArray<Dim, Scalar> moment_values_;   // eigenvalues of the linear moment, ascending
  MatArray<Dim, Scalar> moment_vectors_;  // and its eigenvectors, as columns
};

namespace detail {

// Green-Lagrange strain E = (F^T F - I)/2.
template <int Dim, class Scalar>
Mat<Dim, Scalar> green_strain(const Mat<Dim, Scalar>& f) {
  return Scalar(0.5) * (f.transpose() * f - Mat<Dim, Scalar>::Identity());
}

// St Venant-Kirchhoff second Piola-Kirchhoff stress S = lambda tr(E) I + 2 mu E (eq 6's law
// written on the Green strain so that it is invariant under rigid rotation).
template <int Dim, class Scalar>
Mat<Dim, Scalar> svk_stress(const Mat<Dim, Scalar>& e, const LameConstants<Scalar>& lame) {
  return lame.lambda * e.trace() * Mat<Dim, Scalar>::Identity() + 2 * lame.mu * e;
}

// Strain-energy density of the St Venant-Kirchhoff law, lambda/2 tr(E)^2 + mu E:E.
template <int Dim, class Scalar>
Scalar svk_energy_density(const Mat<Dim, Scalar>& e, const LameConstants<Scalar>& lame) {
  return Scalar(0.5) * lame.lambda * e.trace() * e.trace() + lame.mu * e.squaredNorm();
}

// Cauchy stress sigma = F S F^T / det F.
template <int Dim, class Scalar>
Mat<Dim, Scalar> cauchy_from_svk(const Mat<Dim, Scalar>& f, const LameConstants<Scalar>& lame) {
  const Mat<Dim, Scalar> s = svk_stress(green_strain(f), lame);
  return f * s * f.transpose() / f.determinant();
}

// Cauchy stress of every particle from the fit's deformation gradient at positions x.
template <int Dim, class Scalar>
void fitted_cauchy_stresses(const DeformationFit<Dim, Scalar>& fit, const VecArray<Dim, Scalar>& x,
                            const BondList<Dim, Scalar>& bonds, const LameConstants<Scalar>& lame,
                            MatArray<Dim, Scalar>& sigma) {
  sigma.resize(x.size());
  MPSFSI_OMP(parallel for schedule(static))
  for (std::int64_t ii = 0; ii < static_cast<std::int64_t>(x.size()); ++ii) {
    const auto i = static_cast<std::size_t>(ii);
    sigma[i] = cauchy_from_svk(fit.gradient(x, bonds, i), lame);
  }
}

}  // namespace detail
}  // namespace MPSFSI_ABI
}  // namespace mpsfsi
