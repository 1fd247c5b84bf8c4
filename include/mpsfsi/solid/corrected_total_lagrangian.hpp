// SPDX-License-Identifier: BSD-3-Clause
#pragma once

#include <algorithm>
#include <cstdint>
#include <limits>
#include <vector>

#include "mpsfsi/core/abi.hpp"
#include "mpsfsi/core/parallel.hpp"
#include "mpsfsi/core/types.hpp"
#include "mpsfsi/solid/bonds.hpp"
#include "mpsfsi/solid/deformation.hpp"
#include "mpsfsi/solid/detail/packed_bonds.hpp"

namespace mpsfsi {
inline namespace MPSFSI_ABI {

// A stress-model policy of ElasticSolver provides
//   static constexpr const char* name;
//   void initialize(const BondList&, const SolidModelContext&);
//   void bonds_changed(const BondList&, const std::vector<std::size_t>& particles);  // after cuts
//   void internal_forces(const VecArray& x, const BondList&, VecArray& force);  // overwrites force
//   void stresses(const VecArray& x, const BondList&, MatArray& sigma);  // Cauchy, per particle
//   Scalar strain_energy(const VecArray& x, const BondList&) const;
//   void kick(Scalar dt); void drift(Scalar dt);   // particle rotation, if the model has it
// and optionally internal_forces(x, bonds, force, sigma), the forces and the stresses of x in one
// pass, and internal_forces(x, v, bonds, force, sigma*, viscosity), those with the bond viscosity
// added (docs/extending.md, "Stress model"). internal_forces() is called once per step on the new
// positions; the others on demand.

// Corrected total-Lagrangian solid with the St Venant-Kirchhoff law (docs/theory.md, section 3.3,
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
// alpha (stabilization) is 0.1 by default; the validation cases barely feel it (oscillating plate
// period error +2.84, +2.81, +2.73 % with alpha = 0.02, 0.1, 0.5; docs/validation/solid.md).
template <int Dim, class Scalar = double>
class CorrectedTotalLagrangian {
 public:
  static constexpr const char* name = "corrected total-Lagrangian SVK";
  using vec_type = Vec<Dim, Scalar>;
  using mat_type = Mat<Dim, Scalar>;
  using fit_type = DeformationFit<Dim, Scalar>;
  using affine_type = typename fit_type::affine_type;
  static constexpr int width = fit_type::width;
  // Particles per group of the force loop: one register of doubles (core/abi.hpp), but 8 in 3D
  // where a register holds 4 or more. A 3D particle's fit (3 x 9 sums, a 9 x 9 M^+) is a long
  // chain of dependent multiply-adds, and two AVX2 registers a value keep twice as many chains in
  // flight: the 3D fracture step ran in 0.8 of the time with 8 lanes on AVX2, while 2D (1.05) and
  // 8 lanes on SSE2 (1.1-1.2) did not gain (docs/performance.md, the solid's force loop).
  static constexpr int lanes = Dim == 3 && simd_double_lanes >= 4 ? 8 : simd_double_lanes;

  Scalar stabilization = Scalar(0.1);  // alpha

  void initialize(const BondList<Dim, Scalar>& bonds, const SolidModelContext<Dim, Scalar>& context) {
    context_ = context;
    fit_.build(bonds, context.l0);
    packed_.build(fit_, bonds);
  }

  // Checkpoints (io/checkpoint.hpp): the fits; the packed copy is rebuilt from them.
  template <class Archive>
  void checkpoint_state(Archive& a) {
    fit_.checkpoint_state(a);
  }
  void checkpoint_restored(const BondList<Dim, Scalar>& bonds) {
    fit_.restore_resolved_directions(bonds);
    packed_.build(fit_, bonds);
  }

  // Refits the particles whose bonds were cut.
  void bonds_changed(const BondList<Dim, Scalar>& bonds, const std::vector<std::size_t>& particles) {
    for (const std::size_t i : particles) {
      fit_.rebuild(bonds, i);
      packed_.update(fit_, bonds, i);
    }
  }

  // With t_ij = V P_i g_ij + 2c beta_ij delta_ij per directed bond, f_k = sum_j (t_kj - t_jk).
  // The loop runs over groups of `lanes` consecutive particles, one particle per SIMD lane
  // (detail::PackedBonds), as Eigen arrays of that length: each lane fits its particle's A_i, and
  // the stress of all of them is evaluated at once (with about 12 bonds per particle in 2D, the
  // per-particle work weighs as much as the bond loops). The coefficients are not stored:
  // with g_ij = beta_ij M_i^+ phi_ij (DeformationFit, M_i^+ symmetric),
  //   U_i = sum_j du_ij g_ij^T = (sum_j beta_ij du_ij phi_ij^T) M_i^+,
  //   t_ij = beta_ij (2c du_ij + (V P_i [M_i^+]_(1..d) - 2c U_i) phi_ij),
  // so each bond needs only r0 and beta (and beta |r0| for the viscosity), and each particle its
  // M_i^+. Each lane adds its own t_ij to its particle and subtracts it from particle j's force:
  // thread 0 into `force`, the others into their own copies (partial_), which are added at the
  // end, so no two threads write the same entry. Thread t takes a contiguous block of groups (the
  // t-th share of the bonds), so its copy is written only within the bond graph's bandwidth of
  // that block: only that stretch is zeroed and added (the whole array when the particles are not
  // ordered in space). Each thread keeps the group's r_ij in its own rows of scratch_. Nothing is
  // allocated after the first call.
  void internal_forces(const VecArray<Dim, Scalar>& x, const BondList<Dim, Scalar>& /*bonds*/, VecArray<Dim, Scalar>& force) {
    forces_and_stresses<false>(x, nullptr, force, nullptr, 0);
  }

  // The forces and, from the same fit, the Cauchy stress sigma_i = F_i S_i F_i^T / det F_i of
  // every particle (what stresses() gives at x): the solver asks for both when it reads the
  // stresses at every step (fracture), which then cost no pass over the bonds of their own.
  void internal_forces(const VecArray<Dim, Scalar>& x, const BondList<Dim, Scalar>& /*bonds*/, VecArray<Dim, Scalar>& force,
                       MatArray<Dim, Scalar>& sigma) {
    sigma.resize(x.size());
    forces_and_stresses<false>(x, nullptr, force, sigma.data(), 0);
  }

  // The forces (and the stresses, if `sigma` is given) with the bond viscosity added in the same
  // pass over the bonds: what BondViscosity::add(bonds, x, v, viscosity, force) adds after
  // internal_forces(), to round-off. Each bond's term, viscosity beta_ij |r0_ij|
  // ((v_j - v_i) . r_ij) r_ij / |r_ij|^2, is antisymmetric in i and j, so half of it rides on t_ij
  // (+ to i, - to j) and the reverse bond brings the other half.
  void internal_forces(const VecArray<Dim, Scalar>& x, const VecArray<Dim, Scalar>& v, const BondList<Dim, Scalar>& /*bonds*/,
                       VecArray<Dim, Scalar>& force, MatArray<Dim, Scalar>* sigma, Scalar viscosity) {
    if (sigma) sigma->resize(x.size());
    forces_and_stresses<true>(x, v.data(), force, sigma ? sigma->data() : nullptr, viscosity);
  }

 private:
  template <bool Viscous>
  void forces_and_stresses(const VecArray<Dim, Scalar>& x, const vec_type* const vel, VecArray<Dim, Scalar>& force,
                           mat_type* const cauchy, const Scalar viscosity) {
    using lane_type = Eigen::Array<Scalar, lanes, 1>;
    using lane_map = Eigen::Map<const lane_type>;
    const std::size_t count = x.size();
    const Scalar v = context_.volume;
    const Scalar c2 = 2 * stabilization_constant();
    const Scalar inv_l0 = 1 / context_.l0;
    const Scalar lambda = context_.lame.lambda;
    const Scalar two_mu = 2 * context_.lame.mu;
    const Scalar half_viscosity = Scalar(0.5) * viscosity;
    force.resize(count);
    if (count == 0) return;
    const std::size_t row = packed_.longest_row();
    const int threads = parallel::max_threads();
    // Each thread's rows start on a cache line of their own: with a 16-byte aligned block, two
    // threads' scratch rows shared a line, and that false sharing made the 2-thread step slower than
    // the 1-thread one (1.1 ms against 0.9 ms, 2D benchmark at 16,160 particles).
    constexpr std::size_t line = 64 / sizeof(Scalar);
    const std::size_t stride = (Dim * lanes * row + line - 1) / line * line;
    scratch_.resize(static_cast<std::size_t>(threads) * stride + line);
    partial_.resize(static_cast<std::size_t>(threads - 1) * count);
    const std::uint8_t* const keep = keeps_affine(count) ? keep_->data() : nullptr;
    keep_ = nullptr;  // for this loop only: the caller's vector need not outlive it
    if (keep) kept_.resize(count);
    const std::uint8_t* const held = skips_held(count) ? skip_->data() : nullptr;
    skip_ = nullptr;
    affine_type* const kept = kept_.data();
    // Raw pointers: stores through force would otherwise make the compiler reload every
    // container's data pointer in the inner loops.
    Scalar* const scratch = reinterpret_cast<Scalar*>(
        (reinterpret_cast<std::uintptr_t>(scratch_.data()) + 63) & ~static_cast<std::uintptr_t>(63));
    vec_type* const partial = partial_.data();
    vec_type* const out = force.data();
    const vec_type* const pos = x.data();
    const Index* const neighbors = packed_.neighbors(0);
    const Scalar* const blocks = packed_.block(0);
    const std::size_t groups = packed_.num_groups();
    const std::size_t band = packed_.bandwidth();
    // The first pass asks for the bond stream 2 KiB ahead (clamped to its last slot): in 3D the
    // stream is far larger than the cache, the hardware prefetchers stop at every 4 KiB page, and
    // without it the loop waited on each slot's first loads (docs/performance.md, the solid's
    // force loop).
    const std::size_t total_slots = static_cast<std::size_t>(packed_.end(groups - 1));
    const std::size_t slots_ahead = std::max<std::size_t>(1, 2048 / (slot_size * sizeof(Scalar)));
    // Thread t takes the groups that hold the t-th share of the slots the loop evaluates (work[g]:
    // those before group g), not the t-th share of the groups: skipped groups and the short rows
    // at a body's surface would otherwise leave one thread with more bonds than the other.
    const Offset* work = packed_.group_offsets();
    if (held) {
      work_.resize(groups + 1);
      work_[0] = 0;
      for (std::size_t g = 0; g < groups; ++g)
        work_[g + 1] = work_[g] + (all_held(held, g * lanes, std::min<std::size_t>(lanes, count - g * lanes))
                                       ? 0 : packed_.end(g) - packed_.begin(g));
      work = work_.data();
    }
    auto split = [&](int t, int team) -> std::size_t {
      if (t <= 0) return 0;
      if (t >= team) return groups;
      const Offset share = static_cast<Offset>(static_cast<std::size_t>(work[groups]) * static_cast<std::size_t>(t) /
                                               static_cast<std::size_t>(team));
      return static_cast<std::size_t>(std::lower_bound(work, work + groups, share) - work);
    };
    // Thread t's block of groups, its particles, and the particles its bond loop writes to: that
    // block widened by the bandwidth.
    auto group_block = [&](int t, int team, std::size_t& lo, std::size_t& hi) {
      lo = split(t, team);
      hi = split(t + 1, team);
    };
    auto block = [&](int t, int team, std::size_t& lo, std::size_t& hi) {
      group_block(t, team, lo, hi);
      lo = std::min(count, lo * lanes);
      hi = std::min(count, hi * lanes);
    };
    auto reach = [&](int t, int team, std::size_t& lo, std::size_t& hi) {
      block(t, team, lo, hi);
      lo = lo > band ? lo - band : 0;
      hi = std::min(count, hi + band);
    };
    // phi(r0) = [r0, q(r0)/l0] as DeformationFit::basis, the quadratic part rebuilt from r0.
    auto basis = [inv_l0](const Scalar* slot, lane_type (&phi)[width]) {
      for (int a = 0; a < Dim; ++a) phi[a] = lane_map(slot + packed_type::r0_at(a));
      for (int a = 0, c = Dim; a < Dim; ++a)
        for (int b = a; b < Dim; ++b, ++c) phi[c] = (a == b ? Scalar(0.5) * inv_l0 : inv_l0) * phi[a] * phi[b];
    };
    MPSFSI_OMP(parallel)
    {
      const int thread = parallel::thread_id();
      const int team = parallel::team_size();
      std::size_t block_lo, block_hi;
      block(thread, team, block_lo, block_hi);
      vec_type* const mine = thread == 0 ? out : partial + static_cast<std::size_t>(thread - 1) * count;
      Scalar* const rows_r = scratch + static_cast<std::size_t>(thread) * stride;
      // Every thread zeroes its block of `force` (thread 0 writes all of it below) and the
      // stretch of its own copy that it writes.
      std::fill(out + block_lo, out + block_hi, vec_type::Zero());
      if (thread > 0) {
        std::size_t lo, hi;
        reach(thread, team, lo, hi);
        std::fill(mine + lo, mine + hi, vec_type::Zero());
      }
      MPSFSI_OMP(barrier)
      std::size_t group_lo, group_hi;
      group_block(thread, team, group_lo, group_hi);
      for (std::size_t group = group_lo; group < group_hi; ++group) {
        const std::size_t i0 = group * lanes;
        const std::size_t present = std::min<std::size_t>(lanes, count - i0);  // lanes with a particle
        if (held && all_held(held, i0, present)) {
          write_held(i0, present, cauchy, keep, kept);  // their forces are the zeros written above
          continue;
        }
        const Offset first = packed_.begin(group);
        const auto m = static_cast<std::size_t>(packed_.end(group) - first);
        const Scalar* const inverse = packed_.moments(group);
        // The next group's M^+ is read in order but is not part of the bond stream that the
        // first pass prefetches; without this its first loads waited on memory.
        if (group + 1 < group_hi) prefetch_bytes(packed_.moments(group + 1), moment_bytes);
        lane_type xi[Dim];
        for (std::size_t l = 0; l < lanes; ++l) {
          const vec_type& p = pos[i0 + std::min(l, present - 1)];
          for (int a = 0; a < Dim; ++a) xi[a][l] = p[a];
        }
        // r_ij, and B = sum_j beta_ij du_ij phi_ij^T with du_ij = r_ij - r0_ij.
        lane_type bsum[Dim][width];
        for (int a = 0; a < Dim; ++a)
          for (int c = 0; c < width; ++c) bsum[a][c].setZero();
        for (std::size_t k = 0; k < m; ++k) {
          const Offset s = first + static_cast<Offset>(k);
          const Index* const nb = neighbors + static_cast<std::size_t>(s) * lanes;
          const Scalar* const slot = blocks + static_cast<std::size_t>(s) * slot_size;
          const std::size_t ahead = std::min(static_cast<std::size_t>(s) + slots_ahead, total_slots - 1);
          prefetch_slot(neighbors + ahead * lanes, blocks + ahead * slot_size);
          lane_type d[Dim];
          for (std::size_t l = 0; l < lanes; ++l) {
            const vec_type& xj = pos[nb[l]];
            for (int a = 0; a < Dim; ++a) d[a][l] = xj[a];
          }
          lane_type phi[width];
          basis(slot, phi);
          const lane_type beta = lane_map(slot + packed_type::beta_at);
          for (int a = 0; a < Dim; ++a) {
            d[a] -= xi[a];
            Eigen::Map<lane_type>(rows_r + (k * Dim + static_cast<std::size_t>(a)) * lanes) = d[a];
            const lane_type weighted = beta * (d[a] - phi[a]);
            for (int c = 0; c < width; ++c) bsum[a][c] += weighted * phi[c];
          }
        }
        // U = A_i - [I 0] = B M^+, column by column: each column's Dim sums stay in registers
        // (summed over the stored triangle's order, each entry in memory took a load and a store
        // per term, and the sums into one entry waited on each other's stores).
        lane_type u[Dim][width];
        for (int c = 0; c < width; ++c) {
          lane_type sum[Dim];
          const lane_type m_0c = lane_map(inverse + packed_type::moment_at(0, c));
          for (int a = 0; a < Dim; ++a) sum[a] = bsum[a][0] * m_0c;
          for (int e = 1; e < width; ++e) {
            const lane_type m_ec = lane_map(inverse + packed_type::moment_at(e, c));
            for (int a = 0; a < Dim; ++a) sum[a] += bsum[a][e] * m_ec;
          }
          for (int a = 0; a < Dim; ++a) u[a][c] = sum[a];
        }
        // Particles that read a direction softly: F turned with their bonds (DeformationFit::objective),
        // the fitted F kept for the stress term below.
        mat_type fitted[lanes];
        bool soft_group = false;
        for (std::size_t l = 0; l < present; ++l) {
          if (!fit_.reads_softly(i0 + l)) continue;
          soft_group = true;
          for (int a = 0; a < Dim; ++a)
            for (int b = 0; b < Dim; ++b) fitted[l](a, b) = (a == b ? Scalar(1) : Scalar(0)) + u[a][b][l];
          const mat_type f = fit_.objective(fitted[l], i0 + l);
          for (int a = 0; a < Dim; ++a)
            for (int b = 0; b < Dim; ++b) u[a][b][l] = f(a, b) - (a == b ? Scalar(1) : Scalar(0));
        }
        if (keep)
          for (std::size_t l = 0; l < present; ++l) {
            if (!keep[i0 + l]) continue;
            affine_type& a = kept[i0 + l];
            for (int r = 0; r < Dim; ++r)
              for (int c = 0; c < width; ++c) a(r, c) = (r == c ? Scalar(1) : Scalar(0)) + u[r][c][l];
          }
        // Per lane: F = I + U[:, :Dim], E = (F^T F - I)/2, S = lambda tr(E) I + 2 mu E, and
        // V P = V F S (detail::green_strain, svk_stress, written out lane-wise).
        lane_type e[Dim][Dim];
        for (int a = 0; a < Dim; ++a)
          for (int b = a; b < Dim; ++b) {
            e[a][b] = Scalar(0.5) * (u[a][b] + u[b][a]);
            for (int c = 0; c < Dim; ++c) e[a][b] += Scalar(0.5) * u[c][a] * u[c][b];
            e[b][a] = e[a][b];
          }
        lane_type trace = e[0][0];
        for (int a = 1; a < Dim; ++a) trace += e[a][a];
        lane_type stress[Dim][Dim];
        for (int a = 0; a < Dim; ++a)
          for (int b = 0; b < Dim; ++b) stress[a][b] = two_mu * e[a][b];
        for (int a = 0; a < Dim; ++a) stress[a][a] += lambda * trace;
        lane_type vp[Dim][Dim];
        for (int a = 0; a < Dim; ++a)
          for (int b = 0; b < Dim; ++b) {
            vp[a][b] = stress[a][b];
            for (int c = 0; c < Dim; ++c) vp[a][b] += u[a][c] * stress[c][b];
            vp[a][b] *= v;
          }
        if (cauchy) store_cauchy(u, vp, v, i0, present, cauchy);
        if (soft_group) add_soft_reading_terms(u, bsum, c2, i0, present, fitted, vp);
        // W = V P [M^+]_(1..d) - 2c U, so that t_ij = beta_ij (2c du_ij + W phi_ij).
        // Column by column, as U.
        lane_type w[Dim][width];
        for (int c = 0; c < width; ++c) {
          lane_type sum[Dim];
          for (int a = 0; a < Dim; ++a) sum[a] = -c2 * u[a][c];
          for (int b = 0; b < Dim; ++b) {
            const lane_type m_bc = lane_map(inverse + packed_type::moment_at(b, c));
            for (int a = 0; a < Dim; ++a) sum[a] += vp[a][b] * m_bc;
          }
          for (int a = 0; a < Dim; ++a) w[a][c] = sum[a];
        }
        lane_type vi[Dim];
        if constexpr (Viscous)
          for (std::size_t l = 0; l < lanes; ++l) {
            const vec_type& p = vel[i0 + std::min(l, present - 1)];
            for (int a = 0; a < Dim; ++a) vi[a][l] = p[a];
          }
        lane_type own[Dim];
        for (int a = 0; a < Dim; ++a) own[a].setZero();
        for (std::size_t k = 0; k < m; ++k) {
          const Offset s = first + static_cast<Offset>(k);
          const Index* const nb = neighbors + static_cast<std::size_t>(s) * lanes;
          const Scalar* const slot = blocks + static_cast<std::size_t>(s) * slot_size;
          lane_type phi[width];
          basis(slot, phi);
          const lane_type beta = lane_map(slot + packed_type::beta_at);
          lane_type r[Dim], t[Dim];
          for (int a = 0; a < Dim; ++a) {
            r[a] = lane_map(rows_r + (k * Dim + static_cast<std::size_t>(a)) * lanes);
            lane_type sum = c2 * (r[a] - phi[a]);
            for (int c = 0; c < width; ++c) sum += w[a][c] * phi[c];
            t[a] = beta * sum;
          }
          if constexpr (Viscous) {
            lane_type dv[Dim];
            for (std::size_t l = 0; l < lanes; ++l) {
              const vec_type& vj = vel[nb[l]];
              for (int a = 0; a < Dim; ++a) dv[a][l] = vj[a];
            }
            lane_type rate = (dv[0] - vi[0]) * r[0], length2 = r[0] * r[0];
            for (int a = 1; a < Dim; ++a) {
              rate += (dv[a] - vi[a]) * r[a];
              length2 += r[a] * r[a];
            }
            // A padding slot (beta = 0, r = 0) and coincident particles (r = 0) have rate = 0 and
            // add nothing: the divisor is kept off zero.
            const lane_type weight = lane_map(slot + packed_type::viscous_weight_at);
            const lane_type scale = half_viscosity * weight * rate / length2.max(std::numeric_limits<Scalar>::min());
            for (int a = 0; a < Dim; ++a) t[a] += scale * r[a];
          }
          for (int a = 0; a < Dim; ++a) own[a] += t[a];
          for (std::size_t l = 0; l < lanes; ++l) {
            vec_type& fj = mine[nb[l]];
            for (int a = 0; a < Dim; ++a) fj[a] -= t[a][l];
          }
        }
        for (std::size_t l = 0; l < present; ++l)
          for (int a = 0; a < Dim; ++a) mine[i0 + l][a] += own[a][l];
      }
      if (team > 1) {
        MPSFSI_OMP(barrier)
        for (int t = 1; t < team; ++t) {
          std::size_t lo, hi;
          reach(t, team, lo, hi);
          const vec_type* const theirs = partial + static_cast<std::size_t>(t - 1) * count;
          for (std::size_t i = std::max(lo, block_lo); i < std::min(hi, block_hi); ++i) out[i] += theirs[i];
        }
      }
    }
  }

 public:
  // Cauchy stress at positions x, from the force loop (the same bits as the stresses it gives with
  // the forces; equal to detail::fitted_cauchy_stresses to round-off).
  void stresses(const VecArray<Dim, Scalar>& x, const BondList<Dim, Scalar>& bonds, MatArray<Dim, Scalar>& sigma) {
    internal_forces(x, bonds, unused_force_, sigma);
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

  // The next force loop also keeps the fitted A_i (DeformationFit::affine, to round-off) of each
  // particle that `wanted` marks (nonzero; nullptr: none), if `wanted` has an entry per particle:
  // the failure check reads the stress at the surface from them instead of fitting those
  // particles again.
  void keep_affine(const std::vector<std::uint8_t>* wanted) { keep_ = wanted; }
  // Whether the next force loop keeps A_i for n particles, and the kept A_i (of the positions of
  // the last loop that kept them; other particles' entries are stale).
  bool keeps_affine(std::size_t n) const { return keep_ != nullptr && keep_->size() == n; }
  const std::vector<affine_type>& kept_affine() const { return kept_; }

  // The next force loop may skip the particles that `held` marks (nonzero; nullptr: none), if it
  // has an entry per particle: the caller vouches that they and their bonded neighbours are
  // prescribed with one velocity and unstrained (detail::HeldParticles), so that their forces and
  // stresses are zero and their fits [I 0]. A group of particles that are all held is not
  // evaluated: those are the values it gets.
  void skip_held(const std::vector<std::uint8_t>* held) { skip_ = held; }
  bool skips_held(std::size_t n) const { return skip_ != nullptr && skip_->size() == n; }

 private:
  using packed_type = detail::PackedBonds<Dim, Scalar, lanes>;
  static constexpr std::size_t slot_size = packed_type::rows * lanes;  // scalars in a slot's block

  static constexpr std::size_t moment_bytes = packed_type::moment_rows * lanes * sizeof(Scalar);  // a group's M^+

  // Asks the cache for `count` bytes from `data` on.
  static void prefetch_bytes(const void* data, std::size_t count) {
#if defined(__GNUC__)
    const char* const bytes = static_cast<const char*>(data);
    for (std::size_t byte = 0; byte < count; byte += 64) __builtin_prefetch(bytes + byte);
#else
    static_cast<void>(data);
    static_cast<void>(count);
#endif
  }

  // Asks the cache for a slot of the packed bonds: its neighbour indices and its block of scalars.
  static void prefetch_slot(const Index* neighbors, const Scalar* block) {
    prefetch_bytes(block, slot_size * sizeof(Scalar));
    prefetch_bytes(neighbors, 1);
  }

  static bool all_held(const std::uint8_t* held, std::size_t i0, std::size_t present) {
    return std::all_of(held + i0, held + i0 + present, [](std::uint8_t h) { return h != 0; });
  }

  // A skipped group of held particles: zero stress, and the fit [I 0] where it is kept.
  static void write_held(std::size_t i0, std::size_t present, mat_type* cauchy, const std::uint8_t* keep,
                         affine_type* kept) {
    for (std::size_t l = 0; l < present; ++l) {
      if (cauchy) cauchy[i0 + l].setZero();
      if (keep && keep[i0 + l]) kept[i0 + l] = affine_type::Identity();
    }
  }

  // sigma = (F S) F^T / det F per lane, with F S = vp / V, into the particles i0 .. i0 + present.
  template <class Lane>
  static void store_cauchy(const Lane (&u)[Dim][width], const Lane (&vp)[Dim][Dim], Scalar volume, std::size_t i0,
                           std::size_t present, mat_type* cauchy) {
    for (std::size_t l = 0; l < present; ++l) {
      mat_type f, fs;
      for (int a = 0; a < Dim; ++a)
        for (int b = 0; b < Dim; ++b) {
          f(a, b) = (a == b ? Scalar(1) : Scalar(0)) + u[a][b][l];
          fs(a, b) = vp[a][b][l] / volume;
        }
      cauchy[i0 + l] = fs * f.transpose() / f.determinant();
    }
  }

  // What a soft particle's energy adds to the matrix conjugate to its fitted F (vp = V P). Its F is
  // turned (F_obj) and floored, so neither is the least-squares fit that the stabilisation's
  // derivative assumes: the stabilisation keeps a residual R = sum_j beta_ij delta_ij r0_ij^T =
  // B - (F_obj - I) M (the quadratic part of A is zero for a linear fit), and dU_stab/dF_obj = -2c R.
  // The turn then maps the whole of V P - 2c R back onto the fitted F through
  // DeformationFit::objective_stress_term (docs/theory.md, section 3.3).
  template <class Lane>
  void add_soft_reading_terms(const Lane (&u)[Dim][width], const Lane (&bsum)[Dim][width], Scalar c2, std::size_t i0,
                              std::size_t present, const mat_type (&fitted)[lanes], Lane (&vp)[Dim][Dim]) const {
    for (std::size_t l = 0; l < present; ++l) {
      if (!fit_.reads_softly(i0 + l)) continue;
      mat_type displacement, b, pull;
      for (int a = 0; a < Dim; ++a)
        for (int c = 0; c < Dim; ++c) {
          displacement(a, c) = u[a][c][l];
          b(a, c) = bsum[a][c][l];
          pull(a, c) = vp[a][c][l];
        }
      pull -= c2 * (b - displacement * fit_.moment_matrix(i0 + l));
      pull += fit_.objective_stress_term(fitted[l], pull, i0 + l);
      for (int a = 0; a < Dim; ++a)
        for (int c = 0; c < Dim; ++c) vp[a][c][l] = pull(a, c);
    }
  }

  Scalar stabilization_constant() const {
    return stabilization * context_.lame.mu * context_.volume * Scalar(Dim) / context_.n0;
  }

  SolidModelContext<Dim, Scalar> context_;
  fit_type fit_;
  packed_type packed_;
  VecArray<Dim, Scalar> partial_;  // the forces threads 1.. add up, one copy per thread
  VecArray<Dim, Scalar> unused_force_;  // what stresses() computes besides them
  std::vector<Offset> work_;  // the slots the loop evaluates before each group, when it skips some
  std::vector<Scalar> scratch_;  // r_ij of the group in hand (Dim x lanes per slot), per thread
  const std::vector<std::uint8_t>* keep_ = nullptr;  // whose A_i the next force loop keeps (keep_affine)
  const std::vector<std::uint8_t>* skip_ = nullptr;  // which particles the next force loop may skip (skip_held)
  std::vector<affine_type> kept_;
};

}  // namespace MPSFSI_ABI
}  // namespace mpsfsi
