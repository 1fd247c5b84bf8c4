// SPDX-License-Identifier: BSD-3-Clause
// 2D dam break against Martin & Moyce (1952) and Koshizuka & Oka (1996), and the 3D dam break.
// Data: tests/verification/data/, each file naming its source in its header.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "mpsfsi/fluid/fluid_solver.hpp"
#include "mpsfsi/fluid/water_under_structure.hpp"
#include "mpsfsi/scenes/dam_break.hpp"

using namespace mpsfsi;

namespace {

using Series = std::vector<std::pair<double, double>>;

// Reads the last two numeric columns of a CSV whose comment lines start with '#'.
Series read_series(const std::string& name) {
  std::ifstream in(std::string(MPSFSI_VERIFICATION_DATA) + "/" + name);
  REQUIRE_MESSAGE(in.good(), "cannot read " << name);
  Series s;
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#' || !(std::isdigit(static_cast<unsigned char>(line[0])) || line[0] == '-')) continue;
    std::vector<double> v;
    std::stringstream ss(line);
    std::string cell;
    while (std::getline(ss, cell, ',')) v.push_back(std::stod(cell));
    s.emplace_back(v[v.size() - 2], v[v.size() - 1]);
  }
  return s;
}

double interpolate(const Series& s, double x) {
  if (x <= s.front().first) return s.front().second;
  for (std::size_t k = 1; k < s.size(); ++k)
    if (x <= s[k].first) {
      const double f = (x - s[k - 1].first) / (s[k].first - s[k - 1].first);
      return s[k - 1].second + f * (s[k].second - s[k - 1].second);
    }
  return s.back().second;
}

// RMS of (sim(T - shift) - exp(T)) / exp(T) over experimental points with 0 < T <= t_max.
double rms_deviation(const Series& sim, const Series& exp, double t_max, double shift) {
  double sum = 0;
  int n = 0;
  for (const auto& [t, value] : exp) {
    if (t <= 0 || t > t_max) continue;
    const double d = (interpolate(sim, t - shift) - value) / value;
    sum += d * d;
    ++n;
  }
  return std::sqrt(sum / n);
}

template <class Policies = FluidDefaults<2>>
void dam_break_2d(WallCondition walls, bool density_term_compression_only = true) {
  const double a = 0.25, g = 9.81, l0 = 0.005;
  FluidParameters<2> p;
  p.l0 = l0;
  p.dt = 2e-4;
  p.wall_condition = walls;
  p.density_term_compression_only = density_term_compression_only;
  FluidSolver<2, Policies> solver(scenes::dam_break<2>(a, 2 * a, 4 * a, 0.6, l0), p);
  Series front, height;  // (T, Z/a) and (tau, H/2a)
  const double t_end = 2.6 / std::sqrt(2 * g / a);
  double fastest = 0;  // m/s, any fluid particle at any step
  while (solver.time() < t_end) {
    solver.step();
    for (std::size_t i = 0; i < solver.particles().size(); ++i)
      if (solver.particles().kinds()[i] == ParticleKind::fluid)
        fastest = std::max(fastest, solver.particles().velocities()[i].norm());
    if (solver.step_count() % 10 == 0) {
      const double t = solver.time();
      front.emplace_back(t * std::sqrt(2 * g / a), scenes::surge_front(solver.particles(), l0) / a);
      height.emplace_back(t * std::sqrt(g / a), scenes::column_height(solver.particles(), l0) / (2 * a));
    }
  }
  const Series mm = read_series("dambreak_martin_moyce_front_table.csv");
  const Series ko = read_series("dambreak_koshizuka_oka1996_front_pysph.csv");
  const Series mm_height = read_series("dambreak_martin_moyce_height_table.csv");

  // One time-origin shift for the experiment (the gate of Martin & Moyce took a finite time to
  // clear the column), the least-squares one over 0 <= shift <= 0.5 in T.
  double best_shift = 0, best = rms_deviation(front, mm, 2.5, 0);
  for (double s = 0; s <= 0.5; s += 0.005) {
    const double r = rms_deviation(front, mm, 2.5, s);
    if (r < best) {
      best = r;
      best_shift = s;
    }
  }
  const double unshifted = rms_deviation(front, mm, 2.5, 0);
  const double ko_shifted = rms_deviation(front, ko, 2.5, best_shift);
  const double ko_unshifted = rms_deviation(front, ko, 2.5, 0);
  const double tau_end = height.back().first;
  const double height_rms = rms_deviation(height, mm_height, tau_end, 0);
  MESSAGE("dam break 2D, l0 = a/50: surge front RMS relative deviation for T <= 2.5: Martin & Moyce "
          << unshifted << " unshifted, " << best << " with the experiment's time origin shifted by T = " << best_shift
          << "; Koshizuka & Oka " << ko_unshifted << " unshifted, " << ko_shifted << " with the same shift; "
          << "residual column height vs Martin & Moyce (tau <= " << tau_end << ", no shift) " << height_rms
          << "; fastest fluid particle " << fastest << " m/s (Ritter's ideal dam-break front, 2 sqrt(g 2a): "
          << 2 * std::sqrt(2 * g * a) << " m/s)");
  // 5 %: the accuracy expected of the method against Martin & Moyce's experiment, met on the surge
  // front with the one fitted time-origin shift stated above (measured 3.2 %; 16 % without the
  // shift, usually read as the experiment's finite gate-opening time; docs/validation/fluid.md).
  CHECK(best <= 0.05);
  // The column height needs no shift; held to the same 5 % of the experiment (measured 0.88 %).
  CHECK(height_rms <= 0.05);
}

}  // namespace

TEST_SUITE("verification.fluid") {

TEST_CASE("verification.fluid: dam break 2D against Martin & Moyce and Koshizuka & Oka") {
  dam_break_2d(WallCondition::wall_rows);
}

TEST_CASE("verification.fluid: dam break 2D with Neumann walls") {
  dam_break_2d(WallCondition::neumann);
}

TEST_CASE("verification.fluid: dam break 2D with the settings for water under a structure") {
  // The same case and tolerances with Neumann walls, CentroidDeviationSurface and the full density
  // term, the settings that keep water under a lid (hydrostatic.cpp).
  dam_break_2d<WaterUnderStructure<2>>(WallCondition::neumann, false);
}

TEST_CASE("verification.fluid: dam break 3D at coarse resolution runs to completion") {
  // Completion: no blow-up, no particle leaves the tank, the surge advances. No 3D experiment is
  // compared; the front's lower bound comes from Martin & Moyce's front (below).
  const double a = 0.25, l0 = 0.02;
  FluidParameters<3> p;
  p.l0 = l0;  // dt automatic (Courant 0.2)
  FluidSolver<3> solver(scenes::dam_break<3>(a, 2 * a, 4 * a, 0.6, l0, 0.1), p);
  CHECK_NOTHROW(solver.advance_to(0.4));
  std::size_t outside = 0;  // fluid particles that went through a wall
  for (std::size_t i = 0; i < solver.particles().size(); ++i) {
    if (solver.particles().kinds()[i] != ParticleKind::fluid) continue;
    const auto& x = solver.particles().positions()[i];
    outside += (x[0] < 0 || x[0] > 4 * a || x[1] < 0 || x[1] > 0.1 || x[2] < 0) ? 1 : 0;
  }
  const double front = scenes::surge_front(solver.particles(), l0) / a;
  MESSAGE("dam break 3D, l0 = a/12.5: " << solver.step_count() << " steps to t = 0.4 s, surge front Z/a = " << front);
  CHECK(outside == 0);
  CHECK(front > 3.0);  // T = 3.5 at t = 0.4 s: Martin & Moyce's front is past 3.9 a by T = 3.3
}

}  // TEST_SUITE

TEST_SUITE("validation.fluid") {

TEST_CASE("validation.fluid: dam break 2D with the settings and the own-value gradient") {
  // The same case and tolerances with the settings for water under a structure and the pressure
  // gradient taken about each particle's own pressure (hydrostatic.cpp, water under a long lid).
  dam_break_2d<WaterUnderLongStructure<2>>(WallCondition::neumann, false);
}

}  // TEST_SUITE
