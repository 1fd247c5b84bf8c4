// SPDX-License-Identifier: BSD-3-Clause
// Brittle fracture of ice beams in three-point bending: the paper's Table 1 protocol,
// run by the study in examples/three_point_bending/bending_test.hpp.
#include <doctest/doctest.h>

#include <cmath>
#include <cstdio>

#include "three_point_bending/bending_test.hpp"

namespace {

// Case 02 in 2D with the study's defaults: the baseline of the speed and resolution checks, run
// once for both.
const bending::Result& baseline_case02() {
  static const bending::Result result = bending::run<2>(bending::table1()[0], bending::Options{});
  return result;
}

// The clean break: the crack starts at the bottom of mid-span, runs to the top within 2 l0 of the
// centre line and breaks the beam in two; the load then falls to near zero (5 % of the peak).
// Source: the experiment, one vertical crack below the load point that breaks the beam (the
// paper's Photo 1); 2 l0 allows for the lattice's one-column steps. "Within 2 l0" is read on the
// fracture surface between the two pieces. With `every_failure_within_2l0` it must hold for every
// failed particle too (the 2D study at l0 = 2 mm); at l0 = 1 mm some failures beside the crack
// reach 3 l0, and the 3D runs are not held to it (docs/validation/fracture.md).
// Energy: after the first crack only the indenter feeds energy in (counted), and the solid's
// energy minus that work must not rise by more than 1 % of its value at the crack (conservation).
// The five 2D cases at 2 mm and case 02 at 1 mm rise by at most 0.33 % (the explicit scheme's
// energy error and contact springs switching on at cut bonds); without the weak-direction floor
// of DeformationFit the 1 mm beam shatters and the balance rises 2000-fold.
void check_clean_break(const bending::Result& r, bool every_failure_within_2l0) {
  CAPTURE(r.input.name);
  CAPTURE(r.crack_offset / r.l0);
  CHECK(std::abs(r.crack_start_x) <= r.l0);
  CHECK(r.crack_start_y < r.l0);
  CHECK(r.crack_top >= r.input.height - 2 * r.l0);
  CHECK(r.broken);
  CHECK(r.rows_crossed_once == r.lattice_rows);  // one surface: every row crosses it exactly once
  CHECK(r.fracture_surface_offset >= 0);
  CHECK(r.fracture_surface_offset <= 2 * r.l0 + 1e-12);
  if (every_failure_within_2l0) CHECK(r.crack_offset <= 2 * r.l0 + 1e-12);
  CHECK(r.final_load_fraction < 0.05);
  CHECK(r.energy_at_failure > 0);
  CHECK(r.energy_rise_after_failure < 0.01);
}

// Elastic stiffness P/dd from the history at half the peak load.
double elastic_stiffness(const bending::Result& r) {
  const bending::HistoryRow* best = &r.history.front();
  for (const auto& h : r.history)
    if (std::abs(h.load - 0.5 * r.peak_load) < std::abs(best->load - 0.5 * r.peak_load)) best = &h;
  return best->load / best->deflection;
}

// Timoshenko stiffness of the simply supported beam of modulus e (shear coefficient 5/6), force in N.
double timoshenko_stiffness(const bending::IceBeamCase& c, double e, double nu) {
  const double l = bending::IceBeamCase::span, g = e / (2 * (1 + nu));
  const double inertia = c.width * c.height * c.height * c.height / 12;
  return 1 / (l * l * l / (48 * e * inertia) + l / (4 * 5.0 / 6.0 * g * c.width * c.height));
}

// Case 02 in 3D (the beam's real width) at spacing l0, given the clean-break check without the
// 2 l0 bound on every failure.
void run_3d_case02(double l0) {
  const auto c = bending::table1()[0];
  bending::Options o;
  o.l0 = l0;
  const auto r = bending::run<3>(c, o);
  MESSAGE("3D case 02 (l0 = " << r.l0 << " m, " << r.particles << " particles): P_max " << r.peak_load << " N, eps_f "
                              << r.flexural_strain << " (" << 100 * r.error() << " %), failures within "
                              << r.crack_offset / r.l0 << " l0, broken " << r.broken << ", fracture surface within "
                              << r.fracture_surface_offset / r.l0 << " l0 (" << r.fracture_surface_beyond_2l0 << " of "
                              << r.fracture_surface_crossings << " crossings beyond 2 l0), " << r.wall_seconds << " s");
  check_clean_break(r, false);
  // 5 %: the 3D beam against Table 1 with the material modulus, the tolerance of the 2D study's
  // P_max (the 3D run adds the width's Poisson effect that the plane model leaves out).
  CHECK(std::abs(r.error()) <= 0.05);
}

}  // namespace

TEST_SUITE("verification.fracture") {

TEST_CASE("three-point bending case 02 breaks cleanly at mid-span") {
  const auto c = bending::table1()[0];
  const auto r = bending::run<2>(c, bending::Options{});
  const double k_sim = elastic_stiffness(r), k_theory = timoshenko_stiffness(c, r.youngs_modulus, 0.3);
  MESSAGE("case 02: P_max " << r.peak_load << " N, dd " << r.deflection_at_peak << " m, eps_f " << r.flexural_strain
                            << " vs " << c.flexural_strain() << " (" << 100 * r.error() << " %), stiffness " << k_sim
                            << " N/m vs Timoshenko " << k_theory << ", failures within " << r.crack_offset / r.l0
                            << " l0, fracture surface within " << r.fracture_surface_offset / r.l0 << " l0, "
                            << r.wall_seconds << " s");
  check_clean_break(r, true);
  // 5 %: Timoshenko's stiffness with shear (kappa = 5/6), the bound of the simply supported beam
  // of verification.solid. Measured 834.0 kN/m against Timoshenko's 833.5 with the material modulus
  // (docs/validation/fracture.md).
  CHECK(std::abs(k_sim / k_theory - 1) < 0.05);
}

}

TEST_SUITE("validation.fracture") {

// The five cases with the material modulus (the default): flexural strain within 3 % and P_max
// within 5 % of Table 1 (the experiment). Sources: 3 % is the solid's discretisation error at this
// resolution (the cantilever and beam of verification.solid, +1.5 % and +1.7 % against
// Timoshenko) with the l0 = 1 mm convergence below (1 %); 5 % on P_max because eq 37 turns the
// experiment's P into sigma_f by beam theory, which a continuum beam loaded through roller contact
// meets to a few per cent (docs/validation/fracture.md).
TEST_CASE("three-point bending: all five cases of Table 1") {
  std::string table =
      "\n| case | E MPa | P_sim N | P_exp N | eps_sim | eps_exp | error | failures within | surface within | wall s |\n"
      "|---|---|---|---|---|---|---|---|---|---|\n";
  for (const auto& c : bending::table1()) {
    const auto r = bending::run<2>(c, bending::Options{});
    char line[256];
    std::snprintf(line, sizeof line, "| %s | %.1f | %.1f | %.1f | %.5f | %.5f | %+.1f %% | %.1f l0 | %.1f l0 | %.1f |\n",
                  c.name.c_str(), r.youngs_modulus / 1e6, r.peak_load, c.peak_load, r.flexural_strain,
                  c.flexural_strain(), 100 * r.error(), r.crack_offset / r.l0, r.fracture_surface_offset / r.l0,
                  r.wall_seconds);
    table += line;
    check_clean_break(r, true);
    CAPTURE(c.name);
    CHECK(std::abs(r.error()) <= 0.03);
    CHECK(std::abs(r.peak_load / c.peak_load - 1) <= 0.05);
  }
  MESSAGE(table);
}

// The paper's protocol, Table 1's apparent E as the solid's modulus: the beam deflects by the
// shear term as well, so the flexural strain exceeds Table 1's by Timoshenko's
// s = 2 (1 + nu) h^2 / (kappa L^2) (docs/theory.md, section 6.3). Checked: the excess minus s
// within the 3 % of the material-modulus check above.
TEST_CASE("three-point bending: the apparent modulus deflects by the shear term") {
  std::string table =
      "\n| case | E MPa | P_sim N | eps_sim | eps_exp | error | shear term s |\n|---|---|---|---|---|---|---|\n";
  bending::Options apparent;
  apparent.modulus = bending::Modulus::apparent;
  for (const auto& c : bending::table1()) {
    const auto r = bending::run<2>(c, apparent);
    const double shear_term = c.material_modulus(apparent.poisson_ratio) / c.youngs_modulus() - 1;
    char line[256];
    std::snprintf(line, sizeof line, "| %s | %.1f | %.1f | %.5f | %.5f | %+.1f %% | %.1f %% |\n", c.name.c_str(),
                  r.youngs_modulus / 1e6, r.peak_load, r.flexural_strain, c.flexural_strain(), 100 * r.error(),
                  100 * shear_term);
    table += line;
    check_clean_break(r, true);
    CAPTURE(c.name);
    CHECK(std::abs((1 + r.error()) / (1 + shear_term) - 1) <= 0.03);
    CHECK(std::abs(r.peak_load / c.peak_load - 1) <= 0.05);
  }
  MESSAGE(table);
}

TEST_CASE("three-point bending: halving the loading speed") {
  const auto c = bending::table1()[0];
  bending::Options slow;
  slow.speed = 0.01;
  const auto& fast = baseline_case02();
  const auto half = bending::run<2>(c, slow);
  const double change = half.flexural_strain / fast.flexural_strain - 1;
  MESSAGE("eps_f at 0.02 m/s " << fast.flexural_strain << ", at 0.01 m/s " << half.flexural_strain << " ("
                               << 100 * change << " %)");
  // 1 %: the loading is quasi-static, so the strain must not depend on the rate (measured below
  // 0.01 %; docs/validation/fracture.md).
  CHECK(std::abs(change) <= 0.01);
}

// Cases 02 and 05 at l0 = 1 mm against 2 mm: the flexural strain moves by at most 1 %
// (convergence with resolution; docs/validation/fracture.md gives the measured changes).
TEST_CASE("three-point bending: l0 = 1 mm against 2 mm") {
  for (const std::size_t k : {std::size_t{0}, std::size_t{3}}) {
    const auto c = bending::table1()[k];
    bending::Options fine;
    fine.l0 = 0.001;
    const auto coarse = k == 0 ? baseline_case02() : bending::run<2>(c, bending::Options{});
    const auto r = bending::run<2>(c, fine);
    const double change = r.flexural_strain / coarse.flexural_strain - 1;
    MESSAGE("case " << c.name << ": eps_f at l0 = 2 mm " << coarse.flexural_strain << ", at 1 mm " << r.flexural_strain
                    << " (" << 100 * change << " %), error against Table 1 " << 100 * coarse.error() << " -> "
                    << 100 * r.error() << " %, P_max " << coarse.peak_load << " -> " << r.peak_load
                    << " N, failures within " << r.crack_offset / r.l0 << " l0, fracture surface within "
                    << r.fracture_surface_offset / r.l0 << " l0, " << r.wall_seconds << " s");
    CAPTURE(c.name);
    check_clean_break(r, false);
    CHECK(std::abs(change) <= 0.01);
  }
}

// Known failure: at this coarse resolution the crack starts at the bottom centre and arrests
// there (15 failures in the bottom row, the load keeps rising; docs/validation/fracture.md).
TEST_CASE("three-point bending: case 02 in 3D at l0 = h/8 breaks the same way" * doctest::may_fail()) {
  run_3d_case02(bending::table1()[0].height / 8);  // 4.75 mm
}

}

// A run of about 10 minutes on 2 cores: its own CTest entry, labelled "validation" and "long".
TEST_SUITE("long.fracture") {

// The clean break in 3D at the 2D study's l0 = 2 mm (19 layers, about 10 minutes on 2 cores).
// Measured: two pieces, every one of the 779 rows along x crosses the fracture surface once, all
// within 1.5 l0 of the centre line; flexural strain -0.56 % from Table 1, energy rise +0.00 %
// (docs/validation/fracture.md).
TEST_CASE("three-point bending: case 02 in 3D at l0 = 2 mm breaks the same way") {
  run_3d_case02(0.002);
}

}
