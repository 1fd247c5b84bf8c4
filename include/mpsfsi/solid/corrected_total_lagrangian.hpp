// SPDX-License-Identifier: BSD-3-Clause
#pragma once

#include <cstdint>

#include "mpsfsi/core/parallel.hpp"
#include "mpsfsi/core/types.hpp"
#include "mpsfsi/solid/bonds.hpp"
#include "mpsfsi/solid/deformation.hpp"

namespace mpsfsi {

// A stress-model policy of ElasticSolver provides
//   static constexpr const char* name;
//   void initialize(const BondList&, const SolidModelContext&);   // again after bonds are cut
//   void internal_forces(const VecArray& x, const BondList&, VecArray& force);  // overwrites force
//   void stresses(const VecArray& x, const BondList&, MatArray& sigma);  // Cauchy, per particle
//   Scalar strain_energy(const VecArray& x, const BondList&) const;
//   void kick(Scalar dt); void drift(Scalar dt);   // particle rotation, if the model has it
// internal_forces() is called once per step on the new positions; the others on demand.

// Corrected total-Lagrangian solid with the St Venant-Kirchhoff law (physics-notes section 3,
// the "corrected" model): per particle the deformation gradient F_i of the second-order fit
// (DeformationFit), Green strain E_i, S_i = lambda tr(E) I + 2 mu E, first Piola-Kirchhoff
// P_i = F_i S_i. The forces are the exact negative gradient of the discrete energy
// U = sum_i V psi(E_i) + U_stab, so momentum, angular momentum and (with a symplectic integrator)
// energy are conserved. With F_i = I + sum_j (r_ij - r0_ij) g_ij^T,
//   f_k = V P_k sum_j g_kj - sum_j V P_j g_jk + stabilisation.
// F_i is blind to displacement patterns that are even about i (e.g. a checkerboard), the
// zero-energy modes of every corrected particle scheme. They are stiffened by the energy of the
// part of each bond that the fit does not explain,
//   U_stab = sum_i c sum_j beta_ij |delta_ij|^2,  delta_ij = r_ij - A_i phi(r0_ij),  c = alpha mu V d/n0,
// which vanishes for every affine or quadratic deformation (rigid motion, the patch test and
// pure bending are unaffected) and, because A_i minimises that sum, differentiates to
//   f_k += sum_j 2c beta_kj (delta_kj - delta_jk).
// alpha (stabilization) is 0.1 by default; its effect on the validation cases is in the README.
template <int Dim, class Scalar = double>
class CorrectedTotalLagrangian {
 public:
  static constexpr const char* name = "corrected total-Lagrangian SVK";
  using vec_type = Vec<Dim, Scalar>;
  using mat_type = Mat<Dim, Scalar>;
  using fit_type = DeformationFit<Dim, Scalar>;

  Scalar stabilization = Scalar(0.1);  // alpha

  void initialize(const BondList<Dim, Scalar>& bonds, const SolidModelContext<Dim, Scalar>& context) {
    context_ = context;
    fit_.build(bonds, context.l0);
  }

  // Refits the particles whose bonds were cut.
  void bonds_changed(const BondList<Dim, Scalar>& bonds, const std::vector<std::size_t>& particles) {
    for (const std::size_t i : particles) fit_.rebuild(bonds, i);
  }

  void internal_forces(const VecArray<Dim, Scalar>& x, const BondList<Dim, Scalar>& bonds,
                       VecArray<Dim, Scalar>& force) {
    const auto n = static_cast<std::int64_t>(x.size());
    const Scalar v = context_.volume;
    const Scalar c2 = 2 * stabilization_constant();
    force.resize(x.size());
    const auto& nb = bonds.neighbors();
    const auto& r0 = bonds.reference_vectors();
    const auto& beta = bonds.betas();
    const auto& offsets = bonds.offsets();
    const auto& coeff = fit_.coefficients();
    const auto& reverse = bonds.reverse_links();
    // With t_ij = V P_i g_ij + 2c beta_ij delta_ij per directed bond, f_k = sum_j (t_kj - t_jk):
    // the first pass fits A_i and writes t for i's own bonds, the second gathers the reverse ones.
    bond_terms_.resize(bonds.num_bonds());
    // Raw pointers and local bounds: stores through bond_terms_ and force would otherwise make
    // the compiler reload every container's data pointer and bound in the inner loops.
    vec_type* const terms = bond_terms_.data();
    vec_type* const out = force.data();
    const vec_type* const pos = x.data();
    const Index* const nbp = nb.data();
    const vec_type* const r0p = r0.data();
    const Scalar* const betap = beta.data();
    const Offset* const offp = offsets.data();
    const Offset* const revp = reverse.data();
    const auto* const coeffp = coeff.data();
    MPSFSI_OMP(parallel)
    {
      MPSFSI_OMP(for schedule(static))
      for (std::int64_t i = 0; i < n; ++i) {
        const Offset first = offp[i], last = offp[i + 1];
        const vec_type xi = pos[i];
        // U = A - [I 0] = sum_j du_j g_j^T, du_j = r_ij - r0_ij; delta_ij = du_j - U phi(r0_ij).
        typename fit_type::affine_type u = fit_type::affine_type::Zero();
        for (Offset b = first; b < last; ++b) u.noalias() += (pos[nbp[b]] - xi - r0p[b]) * coeffp[b].transpose();
        const mat_type f = mat_type::Identity() + u.template leftCols<Dim>();
        const mat_type vp = v * f * detail::svk_stress(detail::green_strain(f), context_.lame);
        vec_type own = vec_type::Zero();
        for (Offset b = first; b < last; ++b) {
          const vec_type r0b = r0p[b];
          const vec_type delta = pos[nbp[b]] - xi - r0b - u.template leftCols<Dim>() * r0b -
                                 u.template rightCols<fit_type::quad>() * fit_.quadratic(r0b);
          const vec_type t = vp * coeffp[b].template head<Dim>() + (c2 * betap[b]) * delta;
          terms[b] = t;
          own += t;
        }
        out[i] = own;
      }
      MPSFSI_OMP(for schedule(static))
      for (std::int64_t i = 0; i < n; ++i) {
        const Offset first = offp[i], last = offp[i + 1];
        vec_type sum = out[i];
        for (Offset b = first; b < last; ++b) sum -= terms[revp[b]];
        out[i] = sum;
      }
    }
  }

  // Cauchy stress at positions x.
  void stresses(const VecArray<Dim, Scalar>& x, const BondList<Dim, Scalar>& bonds, MatArray<Dim, Scalar>& sigma) {
    detail::fitted_cauchy_stresses(fit_, x, bonds, context_.lame, sigma);
  }

  // U = sum_i V psi(E_i) + U_stab (the energy whose gradient the forces are).
  Scalar strain_energy(const VecArray<Dim, Scalar>& x, const BondList<Dim, Scalar>& bonds) const {
    const Scalar c = stabilization_constant();
    Scalar total = 0;
    for (std::size_t i = 0; i < x.size(); ++i) {
      const typename fit_type::affine_type a = fit_.affine(x, bonds, i);
      const mat_type f = a.template leftCols<Dim>();
      total += context_.volume * detail::svk_energy_density(detail::green_strain(f), context_.lame);
      for (Offset b = bonds.begin(i); b < bonds.end(i); ++b) {
        const vec_type delta = x[static_cast<std::size_t>(bonds.neighbor(b))] - x[i] - a * fit_.basis(bonds.r0(b));
        total += c * bonds.beta(b) * delta.squaredNorm();
      }
    }
    return total;
  }

  void kick(Scalar) {}
  void drift(Scalar) {}

  const fit_type& fit() const { return fit_; }

 private:
  Scalar stabilization_constant() const {
    return stabilization * context_.lame.mu * context_.volume * Scalar(Dim) / context_.n0;
  }

  SolidModelContext<Dim, Scalar> context_;
  fit_type fit_;
  VecArray<Dim, Scalar> bond_terms_;  // t_ij
};

}  // namespace mpsfsi
