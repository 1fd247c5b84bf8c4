// SPDX-License-Identifier: BSD-3-Clause
#pragma once

#include <cmath>
#include <cstdint>
#include <vector>

#include "mpsfsi/core/abi.hpp"
#include "mpsfsi/core/parallel.hpp"
#include "mpsfsi/core/types.hpp"
#include "mpsfsi/solid/bonds.hpp"
#include "mpsfsi/solid/particle_constraints.hpp"

namespace mpsfsi {
inline namespace MPSFSI_ABI {
namespace detail {

// The particles whose internal force and stress are zero because nothing around them deforms:
// clamped supports, indenters and walls made of particles (a stress model may skip them,
// docs/extending.md). A particle is quiet when it is prescribed and each intact bond of it joins
// a particle prescribed with the same velocity and is unstrained, |r_ij - r0_ij| <= tol |r0_ij|.
// A quiet particle has F = I and no stabilisation residual, so the terms it puts on its bonds
// vanish; a held particle is quiet and bonded only to quiet particles, so the terms its bonds
// bring it vanish as well: its internal force is zero, its stress zero, its fit [I 0]. Such a
// neighbourhood moves by one common translation, so it stays held while its constraints stay.
// tol = 1e-9 bounds the stress ignored at 1e-9 E; the round-off a translation leaves in r_ij is
// about 1e-16 |x| / |r0| a step, so a neighbourhood far from the origin or translated over very
// many steps drops out of the set and is computed again, which is only slower.
template <int Dim>
class HeldParticles {
 public:
  static constexpr double strain_tolerance = 1e-9;

  // Marks the held particles of positions x (held()[i] != 0); returns the marks, or nullptr when
  // no particle is held. No allocation once sized.
  const std::vector<std::uint8_t>* mark(const ParticleConstraints<Dim>& constraints, const BondList<Dim, double>& bonds,
                                        const VecArray<Dim, double>& x) {
    const std::size_t n = x.size();
    quiet_.resize(n);
    held_.resize(n);
    const double tol2 = strain_tolerance * strain_tolerance;
    int any_quiet = 0, any_held = 0;
    MPSFSI_OMP(parallel for schedule(static) reduction(| : any_quiet))
    for (std::int64_t ii = 0; ii < static_cast<std::int64_t>(n); ++ii) {
      const auto i = static_cast<std::size_t>(ii);
      bool quiet = constraints.at(i) == Constraint::prescribed;
      for (Offset b = bonds.begin(i); quiet && b < bonds.end(i); ++b) {
        if (!bonds.intact(b)) continue;
        const auto j = static_cast<std::size_t>(bonds.neighbor(b));
        const auto& r0 = bonds.r0(b);
        quiet = constraints.at(j) == Constraint::prescribed &&
                constraints.prescribed_velocity(j) == constraints.prescribed_velocity(i) &&
                (x[j] - x[i] - r0).squaredNorm() <= tol2 * r0.squaredNorm();
      }
      quiet_[i] = quiet ? 1 : 0;
      any_quiet |= quiet ? 1 : 0;
    }
    if (!any_quiet) return nullptr;
    MPSFSI_OMP(parallel for schedule(static) reduction(| : any_held))
    for (std::int64_t ii = 0; ii < static_cast<std::int64_t>(n); ++ii) {
      const auto i = static_cast<std::size_t>(ii);
      bool held = quiet_[i] != 0;
      for (Offset b = bonds.begin(i); held && b < bonds.end(i); ++b)
        held = !bonds.intact(b) || quiet_[static_cast<std::size_t>(bonds.neighbor(b))] != 0;
      held_[i] = held ? 1 : 0;
      any_held |= held ? 1 : 0;
    }
    return any_held ? &held_ : nullptr;
  }

 private:
  std::vector<std::uint8_t> quiet_, held_;
};

}  // namespace detail
}  // namespace MPSFSI_ABI
}  // namespace mpsfsi
