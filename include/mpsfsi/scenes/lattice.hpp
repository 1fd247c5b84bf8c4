// SPDX-License-Identifier: BSD-3-Clause
#pragma once

#include <cmath>
#include <cstdint>
#include <random>
#include <string>

#include "mpsfsi/core/abi.hpp"
#include "mpsfsi/core/detail/format.hpp"
#include "mpsfsi/core/error.hpp"
#include "mpsfsi/core/particle_set.hpp"
#include "mpsfsi/core/types.hpp"

namespace mpsfsi {
inline namespace MPSFSI_ABI {
namespace scenes {

// Number of lattice points of spacing l0 from lo to hi inclusive, allowing for round-off.
template <class Scalar>
inline std::int64_t lattice_count(Scalar lo, Scalar hi, Scalar l0) {
  return static_cast<std::int64_t>(std::floor((hi - lo) / l0 + Scalar(1e-9))) + 1;
}

// Particles on the square (2D) or cubic (3D) lattice of spacing l0 filling [lower, upper],
// x varying fastest, all of one kind.
// Scalar is deduced from l0 only, so Eigen expressions such as Vec<3>::Zero() work as corners.
template <int Dim, class Scalar = double>
ParticleSet<Dim, Scalar> lattice_box(const typename ParticleSet<Dim, Scalar>::vec_type& lower,
                                     const typename ParticleSet<Dim, Scalar>::vec_type& upper, Scalar l0,
                                     ParticleKind kind = ParticleKind::fluid) {
  if (!(l0 > 0) || !std::isfinite(l0))
    detail::throw_invalid("scenes::lattice_box", "spacing l0 must be positive, got " + detail::format_number(l0));
  if (!lower.allFinite() || !upper.allFinite() || ((upper - lower).array() < 0).any())
    detail::throw_invalid("scenes::lattice_box", "box corners must be finite with lower <= upper");
  std::int64_t count[3] = {1, 1, 1};
  for (int k = 0; k < Dim; ++k) count[k] = lattice_count(lower[k], upper[k], l0);
  ParticleSet<Dim, Scalar> set;
  set.resize(static_cast<std::size_t>(count[0] * count[1] * count[2]));
  std::size_t n = 0;
  for (std::int64_t c = 0; c < count[2]; ++c)
    for (std::int64_t b = 0; b < count[1]; ++b)
      for (std::int64_t a = 0; a < count[0]; ++a) {
        Vec<Dim, Scalar> p;
        p[0] = lower[0] + static_cast<Scalar>(a) * l0;
        p[1] = lower[1] + static_cast<Scalar>(b) * l0;
        if constexpr (Dim == 3) p[2] = lower[2] + static_cast<Scalar>(c) * l0;
        set.positions()[n] = p;
        set.kinds()[n] = kind;
        ++n;
      }
  return set;
}

// Moves every particle by a uniform random offset in [-amplitude, amplitude] per axis, with a
// fixed seed so tests and benchmarks are repeatable.
template <int Dim, class Scalar>
void jitter(ParticleSet<Dim, Scalar>& set, Scalar amplitude, std::uint32_t seed = 12345) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<Scalar> u(-amplitude, amplitude);
  for (auto& p : set.positions())
    for (int k = 0; k < Dim; ++k) p[k] += u(rng);
}

}  // namespace scenes
}  // namespace MPSFSI_ABI
}  // namespace mpsfsi
