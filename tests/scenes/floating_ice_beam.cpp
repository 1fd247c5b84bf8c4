// SPDX-License-Identifier: BSD-3-Clause
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "mpsfsi/scenes/floating_ice_beam.hpp"

using namespace mpsfsi;

TEST_SUITE("scenes") {

// Hetenyi's semi-infinite beam on a Winkler foundation (scenes/floating_ice_beam.hpp): the
// deflection must satisfy the beam equation D w'''' + k w = 0, carry the end load through the
// foundation (integral of k w = P), have M = -D w'' with M(0) = 0 and a shear of P at the end,
// and the largest moment where the header says. Derivatives by central differences of step
// 1e-3 / lambda: truncation error about 1e-6 relative, hence the 1e-4 bounds.
TEST_CASE("scenes.floating_ice_beam: the reference solution solves the beam on an elastic foundation") {
  scenes::FloatingIceBeam s;
  const double P = 20, D = s.flexural_rigidity(), k = s.foundation_modulus(), lambda = s.lambda();
  CHECK(4 * D * std::pow(lambda, 4) == doctest::Approx(k).epsilon(1e-12));
  const double h = 1e-3 / lambda, w0 = s.deflection(P, 0);
  CHECK(w0 == doctest::Approx(2 * P * lambda / k).epsilon(1e-12));
  auto w = [&](double x) { return s.deflection(P, x); };
  for (double x : {0.3 / lambda, 1.0 / lambda, 2.0 / lambda, 3.5 / lambda}) {
    const double d4 = (w(x + 2 * h) - 4 * w(x + h) + 6 * w(x) - 4 * w(x - h) + w(x - 2 * h)) / std::pow(h, 4);
    CHECK(std::abs(D * d4 + k * w(x)) <= 1e-4 * k * w0);
    const double d2 = (w(x + h) - 2 * w(x) + w(x - h)) / (h * h);
    CHECK(std::abs(s.moment(P, x) + D * d2) <= 1e-4 * P / lambda);
  }
  CHECK(s.moment(P, 0) == 0);
  const double shear = (s.moment(P, h) - s.moment(P, 0)) / h;  // dM/dx at the end
  CHECK(std::abs(shear + P) <= 1e-3 * P);
  // The foundation carries the load: integral of k w over [0, 40 / lambda] (trapezoids).
  double integral = 0;
  const int n = 40000;
  const double dx = 40 / lambda / n;
  for (int i = 0; i < n; ++i) integral += 0.5 * dx * k * (w(i * dx) + w((i + 1) * dx));
  CHECK(integral == doctest::Approx(P).epsilon(1e-6));
  // |M| is largest at pi / (4 lambda).
  double best = 0, at = 0;
  for (int i = 0; i <= 4000; ++i) {
    const double x = i * 1e-3 / lambda;
    if (std::abs(s.moment(P, x)) > best) best = std::abs(s.moment(P, x)), at = x;
  }
  CHECK(std::abs(at - s.largest_moment_position()) <= 1e-3 / lambda);
}

// P_f = 0.68 sigma_f (rho_w g h^5 / E)^(1/4) in plane stress, Croasdale's breaking term: the
// exact coefficient is 3^(1/4) sqrt(2) e^(pi/4) / 6 = 0.6804.
TEST_CASE("scenes.floating_ice_beam: the failure load is Croasdale's breaking term") {
  scenes::FloatingIceBeam s;
  const double croasdale = s.tensile_strength *
                           std::pow(s.water_density * s.gravity * std::pow(s.thickness, 5) / s.youngs_modulus, 0.25);
  CHECK(s.failure_load() / croasdale == doctest::Approx(0.6804).epsilon(1e-4));
  // At P_f the top fibre at pi / (4 lambda) carries sigma_f: 6 |M| / h^2.
  const double M = s.moment(s.failure_load(), s.largest_moment_position());
  CHECK(6 * std::abs(M) / (s.thickness * s.thickness) == doctest::Approx(s.tensile_strength).epsilon(1e-12));
  // Plane strain stiffens the beam by 1 / (1 - nu^2): lambda falls by its fourth root.
  scenes::FloatingIceBeam strain = s;
  strain.plane_strain = true;
  CHECK(strain.lambda() / s.lambda() ==
        doctest::Approx(std::pow(1 - s.poisson_ratio * s.poisson_ratio, 0.25)).epsilon(1e-12));
}

TEST_CASE("scenes.floating_ice_beam: particles on one lattice, the beam clear of the water") {
  scenes::FloatingIceBeam s;
  const double l0 = s.thickness / 8;
  std::vector<std::size_t> end_column;
  const auto beam = s.beam_particles(l0, end_column);
  const auto water = s.fluid_particles(l0);
  REQUIRE(end_column.size() == 8);
  for (auto i : end_column) CHECK(beam.positions()[i][0] == doctest::Approx(l0 / 2));
  const double L = s.beam_length_for(l0);
  CHECK(L >= 5 / s.lambda());
  CHECK(L < 5 / s.lambda() + l0);
  CHECK(beam.size() == static_cast<std::size_t>(std::lround(L / l0)) * 8);
  // No water or wall particle closer than l0 to a beam particle, and every water particle in
  // the tank, below the beam or in the open water at most the rounded draft above y_b.
  double closest = 1e300;
  const double yb = s.beam_bottom(l0), level = s.open_water_level(l0);
  CHECK(std::abs(s.level_above_draft(l0)) <= l0 / 2);
  for (std::size_t i = 0; i < water.size(); ++i) {
    const auto& x = water.positions()[i];
    for (std::size_t j = 0; j < beam.size(); j += 7) closest = std::min(closest, (x - beam.positions()[j]).norm());
    if (water.kinds()[i] != ParticleKind::fluid) continue;
    CHECK(x[0] > 0);
    CHECK(x[0] < s.tank_length(l0));
    CHECK(x[1] < (x[0] < L ? yb : level));
  }
  CHECK(closest >= l0 * (1 - 1e-9));
}

// The roller sits at mid-thickness on the end column: of 8 rows the lower middle one (3.5 spacings
// above the bottom), of 7 rows the middle one.
TEST_CASE("scenes.floating_ice_beam: the roller's particle") {
  scenes::FloatingIceBeam s;
  for (const int rows : {8, 7}) {
    const double l0 = s.thickness / rows;
    std::vector<std::size_t> end_column;
    const auto beam = s.beam_particles(l0, end_column);
    const auto roller = s.roller_particle(beam, end_column, l0);
    CHECK(beam.positions()[roller][0] == doctest::Approx(l0 / 2));
    CHECK(beam.positions()[roller][1] == doctest::Approx(s.beam_bottom(l0) + 3.5 * l0));
    CHECK_THROWS_AS(s.roller_particle(beam, {}, l0), InvalidInput);
  }
}

// The wetted bottom face: every column but the end one has exactly one particle in it, the one
// in the bottom row.
TEST_CASE("scenes.floating_ice_beam: the wetted bottom face is the bottom row beyond the end column") {
  scenes::FloatingIceBeam s;
  const double l0 = s.thickness / 4;
  std::vector<std::size_t> end_column;
  const auto beam = s.beam_particles(l0, end_column);
  const auto face = s.wetted_bottom(beam.positions(), l0);
  const auto columns = static_cast<std::size_t>(std::lround(s.beam_length_for(l0) / l0));
  REQUIRE(face.size() == columns - 1);
  for (const auto i : face) {
    CHECK(beam.positions()[i][1] == doctest::Approx(s.beam_bottom(l0) + 0.5 * l0));
    CHECK(beam.positions()[i][0] > l0);
  }
}

// A stress linear through the thickness, sigma_xx = -12 M (y - y_mid) / h^3 (beam theory), carries
// the moment M exactly, at any number of rows; the column is the one x falls in.
TEST_CASE("scenes.floating_ice_beam: the column moment is exact for beam theory's stress") {
  scenes::FloatingIceBeam s;
  for (const int rows : {2, 4, 8}) {
    const double l0 = s.thickness / rows, M = -3.7, mid = s.beam_bottom(l0) + 0.5 * s.thickness;
    std::vector<std::size_t> end_column;
    const auto beam = s.beam_particles(l0, end_column);
    MatArray<2, double> stresses(beam.size(), Mat<2, double>::Zero());
    for (std::size_t i = 0; i < beam.size(); ++i) {
      const auto& x = beam.positions()[i];
      // Only the column at x = 0.3 m carries the moment: the read-out must not mix columns.
      if (std::floor(x[0] / l0) == std::floor(0.3 / l0))
        stresses[i](0, 0) = -12 * M * (x[1] - mid) / std::pow(s.thickness, 3);
    }
    CHECK(s.column_moment(stresses, beam.positions(), 0.3, l0) == doctest::Approx(M).epsilon(1e-12));
    CHECK(s.column_moment(stresses, beam.positions(), 0.3 + l0, l0) == 0.0);
    CHECK_THROWS_AS(s.column_moment(MatArray<2, double>(1), beam.positions(), 0.3, l0), InvalidInput);
  }
}

// The level misses the draft unless the draft is a whole number of rows: 917 kg/m3 ice 80 mm thick
// floats 73.36 mm deep, 3.36 mm below the 7-row level at l0 = 10 mm; at 875 kg/m3 it floats exactly
// 7 rows deep.
TEST_CASE("scenes.floating_ice_beam: the open water's level against the draft") {
  scenes::FloatingIceBeam s;
  s.thickness = 0.08;
  s.ice_density = 917;
  CHECK(s.level_above_draft(0.01) == doctest::Approx(0.07 - 0.07336).epsilon(1e-9));
  s.ice_density = 875;
  CHECK(std::abs(s.level_above_draft(0.01)) < 1e-12);
}

// The level's rise under an end load closes the tank's volume balance: the water Hetenyi's beam,
// lowered by the rise, pushes out from under it raises the open water by that same rise, less what
// the semi-infinite beam displaces beyond the tank's beam, its tail
// (P / k) e^(-lambda L) (cos(lambda L) - sin(lambda L)), 0.84 % of P / k at L = 5 / lambda.
// Checked by the trapezoidal rule on the 80 mm beam (5.06 m), whose error is below 1e-8 of P / k.
TEST_CASE("scenes.floating_ice_beam: the open water's rise under an end load balances the water displaced") {
  scenes::FloatingIceBeam s;
  s.thickness = 0.08;
  const double l0 = 0.01, P = 50, L = s.beam_length_for(l0), rise = s.level_rise(P, l0);
  const int n = 100000;
  double under_beam = 0;
  for (int i = 0; i <= n; ++i) {
    const double x = L * i / n;
    under_beam += (i == 0 || i == n ? 0.5 : 1.0) * (s.deflection(P, x) - rise) * L / n;
  }
  const double open_water = (s.tank_length(l0) - L) * rise, lL = s.lambda() * L;
  const double tail = P / s.foundation_modulus() * std::exp(-lL) * (std::cos(lL) - std::sin(lL));
  CHECK(std::abs(under_beam - open_water + tail) < 1e-6 * P / s.foundation_modulus());
  CHECK(rise == doctest::Approx(P / (1000 * 9.81 * s.tank_length(l0))).epsilon(1e-12));
}

// The column read-out: a beam bent into Hetenyi's shape (each particle moved down by the reference
// deflection at its own x; a column's particles share their x) reads back the reference at each
// column's centre to round-off, with no profile error; the shape scaled by 1.1 gives +10 % at the
// end and an RMS of 0.1 times the reference's own RMS over 0 <= x <= 3 / lambda relative to its end
// value.
TEST_CASE("scenes.floating_ice_beam: column deflections and their error against Hetenyi's") {
  scenes::FloatingIceBeam s;
  const double l0 = s.thickness / 8, P = 20;
  std::vector<std::size_t> end_column;
  const auto beam = s.beam_particles(l0, end_column);
  const auto& reference = beam.positions();
  auto bent = [&](double scale) {
    auto x = reference;
    for (auto& xi : x) xi[1] -= scale * s.deflection(P, xi[0]);
    return x;
  };
  const auto w = s.column_deflections(bent(1), reference, l0);
  REQUIRE(w.size() == static_cast<std::size_t>(std::lround(s.beam_length_for(l0) / l0)));
  const double w_end = s.deflection(P, 0.5 * l0);
  for (std::size_t c = 0; c < w.size(); c += 17)
    CHECK(std::abs(w[c] - s.deflection(P, (c + 0.5) * l0)) <= 1e-12 * w_end);
  const auto exact = s.profile_error(w, P, l0);
  CHECK(std::abs(exact.end) <= 1e-12);
  CHECK(exact.rms <= 1e-12);
  const auto scaled = s.profile_error(s.column_deflections(bent(1.1), reference, l0), P, l0);
  CHECK(scaled.end == doctest::Approx(0.1).epsilon(1e-9));
  double sum = 0;
  std::size_t n = 0;
  for (; (n + 0.5) * l0 <= 3 / s.lambda(); ++n) sum += std::pow(s.deflection(P, (n + 0.5) * l0), 2);
  CHECK(scaled.rms == doctest::Approx(0.1 * std::sqrt(sum / n) / w_end).epsilon(1e-9));
  CHECK_THROWS_AS(s.profile_error({}, P, l0), InvalidInput);
  CHECK_THROWS_AS(s.profile_error(w, 0, l0), InvalidInput);
}

// The 3D strip: the 2D section extruded over the width, 4 rows and 16 particles across a strip 4
// thicknesses wide; the water fills the channel's width under the strip and beside it, between
// side walls; the roller is the end column's lower middle row across the width.
TEST_CASE("scenes.floating_ice_beam: the 3D strip in its channel") {
  scenes::FloatingIceBeam s;
  s.thickness = 0.08;
  s.width = 4 * s.thickness;
  const double l0 = s.thickness / 4, L = s.beam_length_for(l0), W = s.width_for(l0);
  REQUIRE(W == doctest::Approx(0.32));
  const auto columns = static_cast<std::size_t>(std::lround(L / l0)), across = std::size_t{16};
  std::vector<std::size_t> end_column;
  const auto beam = s.beam_particles<3>(l0, end_column);
  CHECK(beam.size() == columns * 4 * across);
  CHECK(end_column.size() == 4 * across);
  const auto roller = s.roller_particles(beam, end_column, l0);
  REQUIRE(roller.size() == across);
  for (const auto i : roller) {
    CHECK(beam.positions()[i][0] == doctest::Approx(l0 / 2));
    CHECK(beam.positions()[i][1] == doctest::Approx(s.beam_bottom(l0) + 1.5 * l0));
  }
  const auto face = s.wetted_bottom(beam.positions(), l0);
  CHECK(face.size() == (columns - 1) * across);
  const auto water = s.fluid_particles<3>(l0);
  const double yb = s.beam_bottom(l0), level = s.open_water_level(l0);
  const auto rows_under = static_cast<std::size_t>(std::lround(yb / l0));
  const auto open_columns = static_cast<std::size_t>(std::lround((s.tank_length(l0) - L) / l0));
  const auto open_rows = static_cast<std::size_t>(std::lround(level / l0));
  std::size_t fluid = 0, near_wall = 0, far_wall = 0, above = 0;
  double closest = 1e300;
  const double tank_top = yb + s.thickness + 2 * l0;
  for (std::size_t i = 0; i < water.size(); ++i) {
    const auto& x = water.positions()[i];
    for (std::size_t j = 0; j < beam.size(); j += 29) closest = std::min(closest, (x - beam.positions()[j]).norm());
    above += x[1] > tank_top;  // the tank is open above, along y, the scene's vertical
    if (water.kinds()[i] != ParticleKind::fluid) {
      near_wall += x[2] < 0;
      far_wall += x[2] > W;
      continue;
    }
    ++fluid;
    CHECK(x[1] < (x[0] < L ? yb : level));
    CHECK(x[2] > 0);
    CHECK(x[2] < W);
  }
  CHECK(fluid == (columns * rows_under + open_columns * open_rows) * across);
  CHECK(near_wall > 0);
  CHECK(far_wall == near_wall);  // a side wall on both sides of the channel
  CHECK(above == 0);
  CHECK(closest >= l0 * (1 - 1e-9));
}

// Per unit width in 3D: beam theory's linear stress across the whole width reads back its moment
// per unit width, and a bent strip its column deflections, as in 2D.
TEST_CASE("scenes.floating_ice_beam: the 3D strip's column moment and deflections") {
  scenes::FloatingIceBeam s;
  s.thickness = 0.08;
  s.width = 0.16;
  const double l0 = s.thickness / 4, M = -3.7, P = 20, mid = s.beam_bottom(l0) + 0.5 * s.thickness;
  std::vector<std::size_t> end_column;
  const auto beam = s.beam_particles<3>(l0, end_column);
  MatArray<3, double> stresses(beam.size(), Mat<3, double>::Zero());
  auto bent = beam.positions();
  for (std::size_t i = 0; i < beam.size(); ++i) {
    const auto& x = beam.positions()[i];
    if (std::floor(x[0] / l0) == std::floor(0.3 / l0))
      stresses[i](0, 0) = -12 * M * (x[1] - mid) / std::pow(s.thickness, 3);
    bent[i][1] -= s.deflection(P, x[0]);
  }
  CHECK(s.column_moment(stresses, beam.positions(), 0.3, l0) == doctest::Approx(M).epsilon(1e-12));
  const auto w = s.column_deflections(bent, beam.positions(), l0);
  CHECK(s.profile_error(w, P, l0).rms <= 1e-12);
  s.width = l0;
  CHECK_THROWS_AS(s.beam_particles<3>(l0, end_column), InvalidInput);  // one particle across
}

TEST_CASE("scenes.floating_ice_beam: spacings that do not fit are refused") {
  scenes::FloatingIceBeam s;
  std::vector<std::size_t> end_column;
  CHECK_THROWS_AS(s.beam_particles(0.003, end_column), InvalidInput);  // 0.04 / 0.003 is not whole
  CHECK_THROWS_AS(s.fluid_particles(0.03), InvalidInput);              // one row through the thickness
  s.water_depth = 0.01;
  CHECK_THROWS_AS(s.fluid_particles(0.005), InvalidInput);             // two rows of water
}

}  // TEST_SUITE
