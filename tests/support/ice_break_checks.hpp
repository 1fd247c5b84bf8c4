// SPDX-License-Identifier: BSD-3-Clause
#pragma once

#include <doctest/doctest.h>

#include <cmath>
#include <string>

#include "floating_ice_beam/beam_on_foundation.hpp"

namespace mpsfsi::test {

// Prints where and when an ice beam first failed and what the break left.
inline void report(const char* what, const floating_ice::BreakResult& r, double x_f) {
  MESSAGE(std::string(what) << ": first failure at t = " << r.first_failure_time << " s, x = " << r.first_failure[0]
                            << " m (" << 100 * (r.first_failure[0] / x_f - 1) << " % from pi/(4 lambda) = " << x_f
                            << "), y = " << r.first_failure[1] << " m; load then (" << r.load_at_failure[0] << ", "
                            << r.load_at_failure[1] << ") N/m; " << r.failures << " failures, " << r.cut_bonds
                            << " bonds cut, " << r.pieces << " pieces of more than 10 particles, "
                            << r.small_fragment_particles << " particles in smaller ones, " << r.beside_two_largest
                            << " outside the two largest, the largest piece from x = "
                            << r.far_piece_start << " m; " << r.wall_seconds << " s");
}

// The clean break of the floating beam's acceptance: two pieces, the far one from within 10 % of
// pi / (4 lambda) (15 % for the coarse 3D strip), and no more than 1 % of the particles shed in
// small fragments.
inline void check_clean_break(const floating_ice::BreakResult& r, double x_f, double tolerance = 0.10) {
  CHECK(r.pieces == 2);
  CHECK(std::abs(r.far_piece_start / x_f - 1) <= tolerance);
  CHECK(r.small_fragment_particles <= r.particles / 100);
}

}  // namespace mpsfsi::test
