// SPDX-License-Identifier: BSD-3-Clause
// The floating ice beam of scenes::FloatingIceBeam on its water, coupled, under an end load: the
// deflection against Hetenyi's semi-infinite beam on a Winkler foundation, and the break against
// his largest moment (docs/validation/fsi.md, "Floating ice beam under an end load"). Long runs (label
// "long"), tens of simulated seconds each.
#include <doctest/doctest.h>

#include <cmath>
#include <cstdio>

#include "floating_ice_beam/beam_in_water.hpp"
#include "support/ice_break_checks.hpp"

using namespace mpsfsi;

TEST_SUITE("long.fsi") {

// Half the breaking load, P = P_f / 2 = 49.1 N/m, after 4 s without load, as a half cosine over
// 10 s (most of a sloshing period, critically damped) and held to 30 s. The ice's inertia scaled
// 16 times lets the ice take 4 times longer steps (its stable step grows as the square root of the
// density): the step is capped at 5 ms, under the water's own viscous limit and, in this quiet
// flow, its Courant limit.
// Asserted at 30 s against Hetenyi's, the acceptance for the floating beam: at h/l0 = 8,
// end column and profile RMS within 5 %, and the fluid's force carrying the ice and the load,
// F = W + P, within 1 % on every 1 s mean from a second after the ramp (measured: +3.6 % at the
// end, RMS 1.3 %, the force within 0.02 %; docs/validation/fsi.md); and both errors smaller than
// at h/l0 = 4, run first (measured there: -21 %, RMS 29 %: the coarser water's particles take
// more room at the same number density and lift the beam). The deflection is measured from the shape at 4 s: unloaded, the beam's ends
// already hang below their start (the corners' load, docs/validation/fsi.md), and the load's
// response adds to that shape.
TEST_CASE("floating beam under an end load: the deflection against Hetenyi's") {
  const auto scene = floating_ice::water_scene();
  REQUIRE(std::abs(scene.level_above_draft(0.01)) < 1e-9);
  const auto load = floating_ice::deflection_load(scene);
  auto run = [&](int rows) {
    const auto settings = floating_ice::water_settings(scene, scene.thickness / rows, 30);
    std::printf("floating beam under an end load, h/l0 = %d: P = %.2f N/m (P_f / 2), Hetenyi's end deflection %.3f mm "
                "less the open water's rise %.3f mm, damping %.3f/s\n", rows, load.ramped,
                1e3 * scene.deflection(load.ramped, 0.5 * settings.l0),
                1e3 * scene.level_rise(load.ramped, settings.l0), settings.damping);
    const auto r = floating_ice::run_in_water<ElasticSolver<2>>(scene, settings, load);
    REQUIRE(!r.blew_up);
    std::printf("floating beam under an end load at 30 s, h/l0 = %d: end %.3f mm from its shape at 4 s (%+.1f %% of "
                "Hetenyi's less the rise), profile RMS %.1f %%; from the far end %+.1f %%, RMS %.1f %%; largest "
                "|F/(W+P) - 1| of a 1 s mean after the ramp %.5f (whole run %.5f); moment at pi/(4 lambda) %+.1f %% of "
                "Hetenyi's (%.3f N m/m before the load); water on the ice %d; fluid solves per step %.2f (at most %d); "
                "%.0f s\n",
                rows, 1e3 * r.at_end.end, 100 * r.at_end.from_start.end, 100 * r.at_end.from_start.rms,
                100 * r.at_end.from_far_end.end, 100 * r.at_end.from_far_end.rms, r.largest_balance_error,
                r.run_balance_error, 100 * r.at_end.moment_error, r.moment_at_start, r.water_on_ice,
                r.fluid_solves_per_step, r.most_fluid_solves, r.wall_seconds);
    return r;
  };
  const auto coarse = run(4);
  const auto r = run(8);
  CHECK(std::abs(r.at_end.from_start.end) <= 0.05);
  CHECK(r.at_end.from_start.rms <= 0.05);
  CHECK(r.largest_balance_error <= 0.01);
  CHECK(std::abs(r.at_end.from_start.end) < std::abs(coarse.at_end.from_start.end));
  CHECK(r.at_end.from_start.rms < coarse.at_end.from_start.rms);
}

// Ramped past P_f with the brittle ice (sigma_f = 30 kPa): after 2 s without load, a half cosine
// over 10 s to 0.9 P_f, held for 2 s, then rising by 0.02 P_f per second, so that a lag of the
// critically damped sloshing, 2 / damping = 2.2 s, costs at most 4.4 % of P_f. The run stops 0.5 s
// after the first failure: on the Winkler foundation the ice breaks through within 0.1 s at its
// own inertia (ice_on_foundation.cpp), and 16 times the inertia slows its motion by sqrt(16).
// Asserted, the acceptance: the first failure at the top surface, within 10 % of
// pi / (4 lambda), at a load within 10 % of P_f, and a clean break in two with the far piece from
// within 10 % of pi / (4 lambda) (as on the Winkler foundation). Measured: x -1.1 %, P -5.5 % (the
// moment at pi / (4 lambda) 6.2 % above Hetenyi's), the far piece from -2.4 % (docs/validation/fsi.md).
TEST_CASE("floating beam under an end load: breaks where and when Hetenyi's moment reaches sigma_f") {
  const auto scene = floating_ice::water_scene();
  const double Pf = scene.failure_load(), x_f = scene.largest_moment_position(), l0 = 0.01;
  const auto load = floating_ice::break_load(scene);
  auto settings = floating_ice::water_settings(scene, l0, 30);
  settings.profile_at = load.unloaded + load.ramp + load.hold;
  std::printf("floating beam ramped past P_f = %.2f N/m: pi / (4 lambda) = %.3f m, damping %.3f/s\n", Pf, x_f,
              settings.damping);
  const auto r = floating_ice::run_in_water<floating_ice::IceSolver>(scene, settings, load);
  REQUIRE(!r.blew_up);
  test::report("floating beam in water, end load", r.broken, x_f);
  std::printf("  at %.0f s, P = %.2f N/m: end %+.1f %% of Hetenyi's less the rise, profile RMS %.1f %%, moment at "
              "pi/(4 lambda) %+.1f %% of Hetenyi's (%.3f N m/m before the load)\n",
              settings.profile_at, r.at_profile.load, 100 * r.at_profile.from_start.end,
              100 * r.at_profile.from_start.rms, 100 * r.at_profile.moment_error, r.moment_at_start);
  std::printf("  load at the first failure %+.1f %% of P_f; largest |F/(W+P) - 1| of a 1 s mean before it %.5f; water "
              "on the ice %d; fluid solves per step %.2f (at most %d); %.0f s\n",
              100 * (-r.broken.load_at_failure[1] / Pf - 1), r.run_balance_error, r.water_on_ice,
              r.fluid_solves_per_step, r.most_fluid_solves, r.wall_seconds);
  REQUIRE(r.broken.failures > 0);
  CHECK(scene.beam_bottom(l0) + scene.thickness - r.broken.first_failure[1] < l0);
  CHECK(std::abs(r.broken.first_failure[0] / x_f - 1) <= 0.10);
  CHECK(std::abs(-r.broken.load_at_failure[1] / Pf - 1) <= 0.10);
  test::check_clean_break(r.broken, x_f);
}

}  // TEST_SUITE
