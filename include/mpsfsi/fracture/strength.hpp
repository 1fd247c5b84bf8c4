// SPDX-License-Identifier: BSD-3-Clause
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <iostream>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "mpsfsi/core/abi.hpp"
#include "mpsfsi/core/error.hpp"
#include "mpsfsi/core/types.hpp"
#include "mpsfsi/fracture/failure_criteria.hpp"

namespace mpsfsi {
inline namespace MPSFSI_ABI {

// What a failure model may read when it assigns each particle its strength (once, when
// ElasticSolver is built).
struct StrengthSetup {
  double tensile_strength = 0;  // SolidParameters::tensile_strength (sigma_f)
  double youngs_modulus = 0;    // E
  double poisson_ratio = 0;     // nu
  double l0 = 0;                // particle spacing
  double particle_volume = 0;   // l0^d (m^2 per unit thickness in 2D, m^3 in 3D)
  const std::vector<Index>* ids = nullptr;  // stable particle ids, one per particle
};

namespace detail {

// A failure model that sets per-particle strengths has
//   void assign_strengths(const StrengthSetup&, std::vector<double>& strength) const;
// one without it gets sigma_f everywhere.
template <class Model, class = void>
struct has_assign_strengths : std::false_type {};
template <class Model>
struct has_assign_strengths<Model, std::void_t<decltype(std::declval<const Model&>().assign_strengths(
                                       std::declval<const StrengthSetup&>(), std::declval<std::vector<double>&>()))>>
    : std::true_type {};

// SplitMix64's finaliser (Steele, Lea & Flood, OOPSLA 2014): a bijective mix of 64 bits.
inline std::uint64_t mix64(std::uint64_t z) {
  z += 0x9e3779b97f4a7c15ULL;
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  return z ^ (z >> 31);
}

// A uniform number in (0, 1) drawn from (seed, particle id) alone, so a particle keeps its
// strength whatever the particle order, thread count or restart, and the numbers are the same
// on every platform (no std:: distribution, whose algorithm the standard leaves open).
inline double uniform_open01(std::uint64_t seed, std::int64_t id) {
  const std::uint64_t bits = mix64(mix64(seed) ^ static_cast<std::uint64_t>(id));
  return (static_cast<double>(bits >> 11) + 0.5) * 0x1.0p-53;  // 53 bits, centred: never 0 or 1
}

}  // namespace detail

// Weakest-link (Weibull) scatter of the tensile strength. A specimen of volume V under a uniform
// stress sigma fails with probability
//   P_f(sigma) = 1 - exp(-(V / V0) (sigma / sigma_0)^m),
// m the Weibull modulus, sigma_0 = SolidParameters::tensile_strength the characteristic strength
// (P_f = 1 - 1/e) of the reference volume V0 (Weibull 1951, J. Appl. Mech. 18:293). Each particle
// is such a specimen of volume V_p = l0^d, so its strength is drawn from
//   sigma_i = sigma_0 (V0 / V_p)^(1/m) (-ln U_i)^(1/m),   U_i uniform in (0, 1),
// and N particles under one stress fail, at their weakest, with the law of the volume N V_p: the
// scatter of a specimen does not depend on l0. `reference_volume` is in m^d (an area per unit
// thickness in 2D); `seed` selects the sample. The criterion (which stress, which plane) is
// Criterion's.
template <class Criterion = MaxPrincipalStress>
struct WeibullStrength : Criterion {
  double modulus = 0;           // m (required)
  double reference_volume = 0;  // V0 in m^d (required)
  std::uint64_t seed = 1;

  WeibullStrength() = default;
  WeibullStrength(double m, double v0, std::uint64_t s = 1, Criterion c = {})
      : Criterion(std::move(c)), modulus(m), reference_volume(v0), seed(s) {}

  // Inverse of P_f for one particle: the strength at cumulative probability u.
  double strength_at(double u, double sigma0, double particle_volume) const {
    return sigma0 * std::pow(reference_volume / particle_volume, 1 / modulus) * std::pow(-std::log(u), 1 / modulus);
  }

  void assign_strengths(const StrengthSetup& s, std::vector<double>& strength) const {
    if (!(std::isfinite(modulus) && modulus > 0))
      detail::throw_invalid("WeibullStrength", "the Weibull modulus m must be set and positive");
    if (!(std::isfinite(reference_volume) && reference_volume > 0))
      detail::throw_invalid("WeibullStrength", "the reference volume V0 must be set and positive");
    const auto& ids = *s.ids;
    strength.resize(ids.size());
    for (std::size_t i = 0; i < ids.size(); ++i)
      strength[i] = strength_at(detail::uniform_open01(seed, ids[i]), s.tensile_strength, s.particle_volume);
  }
};

// A strength that carries a fracture energy G_c: the crack band model's limit for a band wider
// than the material's fracture process zone (Bazant & Oh 1983, Mater. Struct. 16:155). A particle
// that fails cuts a band of width l0 across its plane and releases the strain energy stored there,
// sigma^2 / (2E) per unit volume. Asking that to equal G_c per unit crack area gives
//   sigma_c(l0) = sqrt(2 E G_c / l0),
// the strength used when it is below sigma_f, that is when l0 > h_max = 2 E G_c / sigma_f^2
// (twice the characteristic length E G_c / sigma_f^2); below h_max the band would need a softening
// branch, which a cut that breaks bonds at once cannot represent, and sigma_f governs (a warning
// says so). Near a crack tip the stress a particle samples grows as K / sqrt(l0), so with
// sigma_c ~ 1/sqrt(l0) the load at which a crack grows, and the time a notched specimen starts to
// crack, no longer depend on l0 (docs/theory.md, section 5.6).
template <class Criterion = MaxPrincipalStress>
struct CrackBandStrength : Criterion {
  double fracture_energy = 0;  // G_c in J/m^2 (required)
  bool quiet = false;          // no warning when sigma_f governs

  CrackBandStrength() = default;
  explicit CrackBandStrength(double gc, Criterion c = {}) : Criterion(std::move(c)), fracture_energy(gc) {}

  double band_strength(double youngs_modulus, double l0) const {
    return std::sqrt(2 * youngs_modulus * fracture_energy / l0);
  }

  void assign_strengths(const StrengthSetup& s, std::vector<double>& strength) const {
    if (!(std::isfinite(fracture_energy) && fracture_energy > 0))
      detail::throw_invalid("CrackBandStrength", "the fracture energy G_c must be set and positive");
    const double band = band_strength(s.youngs_modulus, s.l0);
    if (band >= s.tensile_strength && !quiet)
      std::cerr << "warning: CrackBandStrength: l0 = " << s.l0 << " m is below h_max = 2 E G_c / sigma_f^2 = "
                << 2 * s.youngs_modulus * fracture_energy / (s.tensile_strength * s.tensile_strength)
                << " m: the strength is sigma_f and the fracture energy plays no part\n";
    strength.assign(s.ids->size(), std::min(band, s.tensile_strength));
  }
};

}  // namespace MPSFSI_ABI
}  // namespace mpsfsi
