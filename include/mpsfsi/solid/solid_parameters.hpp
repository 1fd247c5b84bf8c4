// SPDX-License-Identifier: BSD-3-Clause
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "mpsfsi/core/abi.hpp"
#include "mpsfsi/core/error.hpp"
#include "mpsfsi/core/types.hpp"

namespace mpsfsi {
inline namespace MPSFSI_ABI {

// How a 2D solid is read out of plane (docs/theory.md, section 3.1). Plane strain keeps the 3D Lame
// constants; plane stress replaces lambda by lambda* = 2 lambda mu / (lambda + 2 mu). Ignored in 3D.
enum class PlaneModel { plane_strain, plane_stress };

// How a failing particle's crack plane divides its bonds (docs/theory.md, section 5.3). The
// principal direction has no sign. slab: the particle keeps neither side; it loses its bonds
// across both faces of its own slab, |(x - x_c) . n_c| < l0/2, and is cut out: the crack is one
// spacing wide, and no sign is used, so a mirror image of the solid cracks as the mirror image.
// fixed_sign: the particle keeps its side towards +x (n_x >= 0). attachment: it keeps the side
// that holds it more firmly (orient_toward_attachment, crack_plane.hpp).
enum class CrackSide { slab, fixed_sign, attachment };

// Lame constants of an isotropic material, eq 7, already reduced for plane stress when asked.
template <class Scalar = double>
struct LameConstants {
  Scalar lambda = 0;
  Scalar mu = 0;
};

// Physical and numerical parameters of ElasticSolver. SI units. In 2D every extensive quantity
// (mass, force, energy) is per unit thickness.
template <int Dim, class Scalar = double>
struct SolidParameters {
  Scalar l0 = 0;              // initial particle spacing (required)
  Scalar density = 0;         // rho_s (required)
  Scalar youngs_modulus = 0;  // E (required)
  Scalar poisson_ratio = -2;  // nu (required; -2 marks "not set")
  PlaneModel plane_model = PlaneModel::plane_strain;
  Vec<Dim, Scalar> gravity = Vec<Dim, Scalar>::Zero();
  // Bonds are the pairs closer than re = re_ratio l0 in the initial configuration.
  Scalar re_ratio = Scalar(2.1);
  // Time step: fixed when dt > 0, else automatic, dt = courant l0 / c with c the faster of the
  // P-wave speed and the contact wave speed. A fixed dt above max_courant l0 / c is an error
  // (a warning if warn_only_on_unstable_dt). The limit 0.5 was measured on the oscillating plate
  // (H/l0 = 10, default model): stable over a period at 0.55, blown up within 41 steps at 0.6.
  Scalar dt = 0;
  Scalar courant = Scalar(0.25);
  Scalar max_courant = Scalar(0.5);
  bool warn_only_on_unstable_dt = false;
  // Mass-proportional damping rate (1/s): a = ... - damping v. Zero by default; only for
  // reaching a static state (dynamic relaxation) or quasi-static loading.
  Scalar damping = 0;
  // Bond viscosity zeta: a damping force along each intact bond on its rate of stretch,
  //   f_i = zeta rho c V (d/n0) sum_j w0_ij ((v_j - v_i) . e_ij) e_ij / |r0_ij|,
  // c the P-wave speed. Central, so rigid motion is not damped and momentum and angular momentum
  // are kept; it damps grid-scale ringing at a ratio of about zeta pi/2 and a bending mode of
  // wavelength L by about zeta (l0/L). Negative (the default): the solver chooses, 0 without a
  // failure criterion and fracture_bond_viscosity with one, because brittle fracture needs it (a
  // bond cut releases its strain energy into grid-scale waves that otherwise break bonds far from
  // the crack: docs/theory.md, section 3.6). ElasticSolver::parameters() shows the value used.
  Scalar bond_viscosity = Scalar(-1);
  static constexpr Scalar fracture_bond_viscosity = Scalar(0.2);
  // Penalty contact between particles that are not bonded (other bodies, cut bonds): a
  // repulsion k (d_c - r) along the line of centres for r < d_c, with d_c = contact_distance_ratio
  // l0 and k = contact_stiffness_ratio E l0^(d-2) (a spring as stiff as one particle's column of
  // material: its frequency sqrt(k/m) = sqrt(ratio E/rho)/l0, which enters the stable dt).
  Scalar contact_distance_ratio = Scalar(1.0);
  Scalar contact_stiffness_ratio = Scalar(1.0);
  // zeta of the contact dashpot (contact.hpp). Off by default: at 0.2 the two halves of the
  // bending study's case 04 stayed joined 5 ms after the crack, at 0 they separate.
  Scalar contact_damping_ratio = Scalar(0);
  // Coulomb friction coefficient mu of the contact (contact.hpp): 0, frictionless, by default.
  Scalar contact_friction = Scalar(0);
  // Brittle failure (used only when the failure policy is not NoFailure): tensile strength
  // sigma_f (required then) and the crack's half-width Cw l0 along the plane (eq 35), with
  // Cw = crack_width_ratio, 0 selecting sqrt(d)/2; l0/2 <= Cw l0 <= re.
  Scalar tensile_strength = std::numeric_limits<Scalar>::infinity();
  Scalar crack_width_ratio = 0;
  // How a failing particle's plane divides its bonds. slab (default) and attachment keep mirror
  // symmetry; fixed_sign breaks it (a symmetric double-notched plate cracks asymmetrically), and
  // attachment lets the crack of a bending beam zigzag along the particle column it runs in, so
  // one of the five beams of the bending study does not break (docs/validation/fracture.md,
  // mirror symmetry).
  CrackSide crack_side = CrackSide::slab;
  // The stress the criterion reads: averaged over the particle and its intact bonds
  // (average_failure_stress), and, with a stress model that fits a second-order field
  // (CorrectedTotalLagrangian), sampled at the body's surface for surface particles: l0/2 along
  // the outward normal, where the continuum's surface is, instead of at the particle centre
  // (fracture/failure_stress.hpp).
  bool average_failure_stress = true;
  bool failure_stress_at_surface = true;
  // A blow-up is declared when a particle moves faster than this multiple of the P-wave speed.
  Scalar blowup_speed_factor = Scalar(1);

  Scalar re() const { return re_ratio * l0; }

  // Lame constants, eq 7, with the plane-stress reduction in 2D when selected.
  LameConstants<Scalar> lame() const {
    const Scalar E = youngs_modulus, nu = poisson_ratio;
    LameConstants<Scalar> c{E * nu / ((1 + nu) * (1 - 2 * nu)), E / (2 * (1 + nu))};
    if (Dim == 2 && plane_model == PlaneModel::plane_stress) c.lambda = 2 * c.lambda * c.mu / (c.lambda + 2 * c.mu);
    return c;
  }

  // P-wave speed sqrt((lambda + 2 mu)/rho) of the (possibly plane-stress) material.
  Scalar p_wave_speed() const {
    const auto c = lame();
    return std::sqrt((c.lambda + 2 * c.mu) / density);
  }

  // The speed that sets the explicit stability limit: P waves or the contact springs.
  Scalar signal_speed() const {
    return std::max(p_wave_speed(), std::sqrt(contact_stiffness_ratio * youngs_modulus / density));
  }

  Scalar stable_dt() const { return courant * l0 / signal_speed(); }
  Scalar max_stable_dt() const { return max_courant * l0 / signal_speed(); }

  Scalar crack_half_width() const {
    return (crack_width_ratio > 0 ? crack_width_ratio : std::sqrt(Scalar(Dim)) / 2) * l0;
  }

  Scalar contact_distance() const { return contact_distance_ratio * l0; }
  Scalar contact_stiffness() const {
    return contact_stiffness_ratio * youngs_modulus * (Dim == 3 ? l0 : Scalar(1));
  }

  // Throws InvalidInput naming the first parameter that is missing or out of range.
  void validate() const {
    auto need = [](bool ok, const std::string& what) {
      if (!ok) detail::throw_invalid("SolidParameters", what);
    };
    need(std::isfinite(l0) && l0 > 0, "l0 (particle spacing) must be set and positive");
    need(std::isfinite(density) && density > 0, "density (rho_s) must be set and positive");
    need(std::isfinite(youngs_modulus) && youngs_modulus > 0, "youngs_modulus (E) must be set and positive");
    need(std::isfinite(poisson_ratio) && poisson_ratio > -1 && poisson_ratio < Scalar(0.5),
         "poisson_ratio (nu) must be set and lie in (-1, 0.5)");
    need(gravity.allFinite(), "gravity must be finite");
    need(std::isfinite(re_ratio) && re_ratio > 1, "re_ratio must exceed 1 (re > l0)");
    need(std::isfinite(dt) && dt >= 0, "dt must be >= 0 (0 selects the automatic step)");
    need(courant > 0 && courant <= max_courant, "courant must lie in (0, max_courant]");
    need(std::isfinite(damping) && damping >= 0, "damping must be >= 0");
    need(std::isfinite(bond_viscosity), "bond_viscosity must be finite (negative: chosen by the solver)");
    need(std::isfinite(contact_distance_ratio) && contact_distance_ratio > 0, "contact_distance_ratio must be positive");
    need(std::isfinite(contact_stiffness_ratio) && contact_stiffness_ratio >= 0, "contact_stiffness_ratio must be >= 0");
    need(std::isfinite(contact_damping_ratio) && contact_damping_ratio >= 0, "contact_damping_ratio must be >= 0");
    need(std::isfinite(contact_friction) && contact_friction >= 0, "contact_friction (mu) must be >= 0");
    need(blowup_speed_factor > 0, "blowup_speed_factor must be positive");
    need(tensile_strength > 0 && !std::isnan(tensile_strength), "tensile_strength (sigma_f) must be positive");
    need(crack_width_ratio == 0 || (crack_half_width() >= l0 / 2 && crack_half_width() <= re()),
         "crack_width_ratio must give l0/2 <= Cw l0 <= re (or be 0 for sqrt(d)/2)");
  }
};

}  // namespace MPSFSI_ABI
}  // namespace mpsfsi
