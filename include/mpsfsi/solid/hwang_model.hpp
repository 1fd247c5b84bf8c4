// SPDX-License-Identifier: BSD-3-Clause
#pragma once

#include <cmath>
#include <cstdint>

#include <Eigen/Geometry>

#include "mpsfsi/core/abi.hpp"
#include "mpsfsi/core/parallel.hpp"
#include "mpsfsi/core/types.hpp"
#include "mpsfsi/solid/bonds.hpp"
#include "mpsfsi/solid/deformation.hpp"

namespace mpsfsi {
inline namespace MPSFSI_ABI {

// The paper's structure model (eqs 16-17 with particle rotation, eq 8; Hwang et al. 2014, 2016),
// read as docs/theory.md, section 3.4 describes:
//   volumetric strain (eq 17)  eps_i = (d / n0_i) sum_j (|r_ij| - |r0_ij|) / |r0_ij| w0_ij,
//                              n0_i the particle's own reference number density;
//   volumetric force           f_i = V lambda (d/n0) sum_j (eps_i + eps_j) (r_ij/|r_ij|) w0_ij/|r0_ij|
//                              (the MPS gradient of lambda eps in its symmetric, momentum-
//                              conserving form; traction-free surfaces follow from it);
//   shear force                f_ij = V 2 mu (2d/(lambda_L n0)) w0_ij (r_ij - R_ij r0_ij)
//                              (2 mu lap(dx) of eq 16, with the displacement of j seen from the
//                              pair's mean rotated frame R_ij = (R_i + R_j)/2 so that rigid
//                              rotation is stress-free and f_ji = -f_ij);
//   particle rotation (eq 8)   I dw_i/dt = sum_j (r_ij/2) x f_ij,  I = m l0^2 / 6,
//                              the torque that returns angular momentum lost by the non-central
//                              shear forces.
// Stress for output and fracture is the St Venant-Kirchhoff stress of the corrected deformation
// gradient (DeformationFit, the same as the corrected model's), so the two models are compared on equal terms.
template <int Dim, class Scalar = double>
class HwangModel {
 public:
  static constexpr const char* name = "paper (eqs 16-17 + rotation)";
  using vec_type = Vec<Dim, Scalar>;
  using mat_type = Mat<Dim, Scalar>;
  static constexpr int spin_dim = Dim == 2 ? 1 : 3;
  using spin_type = Eigen::Matrix<Scalar, spin_dim, 1>;

  void initialize(const BondList<Dim, Scalar>& bonds, const SolidModelContext<Dim, Scalar>& context) {
    context_ = context;
    const std::size_t n = bonds.num_particles();
    fit_.build(bonds, context.l0);
    own_n0_.resize(n);
    for (std::size_t i = 0; i < n; ++i) own_n0_[i] = reference_density(bonds, i);
    if (rotation_.size() != n) {
      rotation_.assign(n, mat_type::Identity());
      spin_.assign(n, spin_type::Zero());
      torque_.assign(n, spin_type::Zero());
    }
    strain_.assign(n, 0);
  }

  // Refits the particles whose bonds were cut and updates their reference number density.
  // Checkpoints (io/checkpoint.hpp): the fits and each particle's frame, spin and torque.
  template <class Archive>
  void checkpoint_state(Archive& a) {
    fit_.checkpoint_state(a);
    a.array(own_n0_);
    a.array(strain_);
    a.array(rotation_);
    a.array(spin_);
    a.array(torque_);
  }
  void checkpoint_restored(const BondList<Dim, Scalar>& bonds) { fit_.restore_resolved_directions(bonds); }

  void bonds_changed(const BondList<Dim, Scalar>& bonds, const std::vector<std::size_t>& particles) {
    for (const std::size_t i : particles) {
      fit_.rebuild(bonds, i);
      own_n0_[i] = reference_density(bonds, i);
    }
  }

  void internal_forces(const VecArray<Dim, Scalar>& x, const BondList<Dim, Scalar>& bonds,
                       VecArray<Dim, Scalar>& force) {
    const auto n = static_cast<std::int64_t>(x.size());
    const Scalar v = context_.volume, d = Scalar(Dim);
    const Scalar vol_coeff = v * context_.lame.lambda * d / context_.n0;
    const Scalar shear_coeff = v * 2 * context_.lame.mu * 2 * d / (context_.lap_lambda * context_.n0);
    force.resize(x.size());
    MPSFSI_OMP(parallel)
    {
      MPSFSI_OMP(for schedule(static))
      for (std::int64_t ii = 0; ii < n; ++ii) {  // eq 17
        const auto i = static_cast<std::size_t>(ii);
        Scalar sum = 0;
        for (Offset b = bonds.begin(i); b < bonds.end(i); ++b) {
          const Scalar len0 = bonds.r0(b).norm();
          const Scalar len = (x[static_cast<std::size_t>(bonds.neighbor(b))] - x[i]).norm();
          sum += (len - len0) / len0 * bonds.weight(b);
        }
        strain_[i] = own_n0_[i] > 0 ? d * sum / own_n0_[i] : Scalar(0);
      }
      MPSFSI_OMP(for schedule(static))
      for (std::int64_t ii = 0; ii < n; ++ii) {  // eq 16 and the torque of eq 8
        const auto i = static_cast<std::size_t>(ii);
        vec_type f = vec_type::Zero();
        spin_type tau = spin_type::Zero();
        for (Offset b = bonds.begin(i); b < bonds.end(i); ++b) {
          const auto j = static_cast<std::size_t>(bonds.neighbor(b));
          const Scalar w0 = bonds.weight(b);
          if (w0 == 0) continue;
          const vec_type r = x[j] - x[i];
          const Scalar len = r.norm(), len0 = bonds.r0(b).norm();
          f += vol_coeff * (strain_[i] + strain_[j]) * w0 / len0 * (r / len);
          const vec_type shear =
              shear_coeff * w0 * (r - Scalar(0.5) * (rotation_[i] + rotation_[j]) * bonds.r0(b));
          f += shear;
          tau += cross(Scalar(0.5) * r, shear);
        }
        force[i] = f;
        torque_[i] = tau;
      }
    }
  }

  void stresses(const VecArray<Dim, Scalar>& x, const BondList<Dim, Scalar>& bonds, MatArray<Dim, Scalar>& sigma) {
    detail::fitted_cauchy_stresses(fit_, x, bonds, context_.lame, sigma);
  }

  // The model has no potential of its own; its strain energy is measured with the SVK energy of
  // the corrected deformation gradient (the energy of the continuum it approximates).
  Scalar strain_energy(const VecArray<Dim, Scalar>& x, const BondList<Dim, Scalar>& bonds) const {
    Scalar total = 0;
    for (std::size_t i = 0; i < x.size(); ++i)
      total += context_.volume * detail::svk_energy_density(
                                     detail::green_strain(fit_.gradient(x, bonds, i)),
                                     context_.lame);
    return total;
  }

  // Half-step update of the spin, I dw/dt = torque (eq 8).
  void kick(Scalar dt) {
    const Scalar inertia = context_.density * context_.volume * context_.l0 * context_.l0 / 6;
    for (std::size_t i = 0; i < spin_.size(); ++i) spin_[i] += dt / inertia * torque_[i];
  }

  // Rotates every particle frame by its spin over dt.
  void drift(Scalar dt) {
    for (std::size_t i = 0; i < spin_.size(); ++i) rotation_[i] = increment(dt * spin_[i]) * rotation_[i];
  }

  // Spin of particle i (rad/s; the z component in 2D). Set it to start a rigid rotation.
  spin_type& spin(std::size_t i) { return spin_[i]; }

 private:
  // n0_i: the particle's own reference number density over its intact bonds (eq 17).
  static Scalar reference_density(const BondList<Dim, Scalar>& bonds, std::size_t i) {
    Scalar n0 = 0;
    for (Offset b = bonds.begin(i); b < bonds.end(i); ++b) n0 += bonds.weight(b);
    return n0;
  }

  static spin_type cross(const vec_type& a, const vec_type& b) {
    if constexpr (Dim == 2) return spin_type(a[0] * b[1] - a[1] * b[0]);
    else return a.cross(b);
  }

  // Rotation by the angle vector phi (Rodrigues' formula in 3D).
  static mat_type increment(const spin_type& phi) {
    if constexpr (Dim == 2) {
      const Scalar c = std::cos(phi[0]), s = std::sin(phi[0]);
      mat_type r;
      r << c, -s, s, c;
      return r;
    } else {
      const Scalar angle = phi.norm();
      if (angle == 0) return mat_type::Identity();
      return Eigen::AngleAxis<Scalar>(angle, phi / angle).toRotationMatrix();
    }
  }

  SolidModelContext<Dim, Scalar> context_;
  DeformationFit<Dim, Scalar> fit_;
  std::vector<Scalar> own_n0_, strain_;
  MatArray<Dim, Scalar> rotation_;
  std::vector<spin_type> spin_, torque_;
};

}  // namespace MPSFSI_ABI
}  // namespace mpsfsi
