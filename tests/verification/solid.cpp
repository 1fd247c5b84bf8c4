// SPDX-License-Identifier: BSD-3-Clause
// Verification of ElasticSolver: vibration, static bending, rigid motion. Every case runs with
// the default (corrected total-Lagrangian) model and, in the "both models" cases, with the paper's
// model too; the figures are printed side by side. docs/validation/solid.md lists them with the
// source of each tolerance.
#include <doctest/doctest.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "mpsfsi/scenes/oscillating_plate.hpp"
#include "mpsfsi/scenes/solid_block.hpp"
#include "mpsfsi/solid/elastic_solver.hpp"
#include "support/tolerance.hpp"

using namespace mpsfsi;

namespace {

struct PlateResult {
  double period = 0;        // from the tip's zero crossings
  double energy_drift = 0;  // max |E(t) - E(0)| / E(0)
  double amplitude = 0;     // largest tip displacement
  std::size_t particles = 0;
};

// Gray, Monaghan & Swift (2001) plate; reference: the analytic thin-plate period of
// scenes::OscillatingPlate (T = 0.25403 s plane strain, H = 0.02 m, vf = 0.01).
template <int Dim, class Policies>
PlateResult run_plate(int layers, double periods) {
  scenes::OscillatingPlate plate;
  const double l0 = plate.thickness / layers;
  std::vector<std::size_t> clamped;
  std::size_t tip = 0;
  auto set = plate.particles<Dim>(l0, 4, clamped, tip);
  SolidParameters<Dim> p;
  p.l0 = l0;
  plate.set_material(p);
  p.plane_model = PlaneModel::plane_strain;
  ElasticSolver<Dim, Policies> s(set, p);
  for (const auto i : clamped) s.clamp(i);
  const double t_ref = plate.period(Dim == 2);
  const double e0 = s.total_energy();
  const double y0 = s.particles().positions()[tip][1];
  PlateResult r;
  r.particles = s.particles().size();
  std::vector<double> crossings;
  double previous = 0;
  while (s.time() < periods * t_ref) {
    s.step();
    const double y = s.particles().positions()[tip][1] - y0;
    if ((previous < 0) != (y < 0) && s.step_count() > 1)
      crossings.push_back(s.time() - s.last_dt() * y / (y - previous));
    previous = y;
    r.amplitude = std::max(r.amplitude, std::abs(y));
    if (s.step_count() % 500 == 0) r.energy_drift = std::max(r.energy_drift, std::abs(s.total_energy() - e0) / e0);
  }
  r.energy_drift = std::max(r.energy_drift, std::abs(s.total_energy() - e0) / e0);
  if (crossings.size() >= 2)
    r.period = 2 * (crossings.back() - crossings.front()) / static_cast<double>(crossings.size() - 1);
  return r;
}

// Static deflection by dynamic relaxation: mass-proportional damping at twice the first
// natural frequency (critical for that mode) and run for 12/omega_1, leaving e^-12 of the
// transient.
template <int Dim, class Policies>
void relax(ElasticSolver<Dim, Policies>& s, double omega1) {
  const double end = s.time() + 12 / omega1;
  while (s.time() < end) s.step();
}

// Cantilever, plane stress, L/h = 10, h/l0 = 10, tip load P (per unit width) spread over the tip
// column, clamped over 4 columns at x < 0. Returns {simulated, Timoshenko} tip deflection at the
// load's line of action x_P = L - l0/2.
template <class Policies>
std::pair<double, double> run_cantilever(int layers = 10) {
  const double h = 0.02, length = 0.2, l0 = h / layers, e = 1e7, nu = 0.3, rho = 1000, load = 0.5;
  auto set = scenes::material_block<2>(Vec<2>(-4 * l0, -h / 2), Vec<2>(length, h / 2), l0);
  SolidParameters<2> p;
  p.l0 = l0;
  p.density = rho;
  p.youngs_modulus = e;
  p.poisson_ratio = nu;
  p.plane_model = PlaneModel::plane_stress;
  const double inertia = h * h * h / 12;
  const double omega1 = std::pow(1.875104 / length, 2) * std::sqrt(e * inertia / (rho * h));
  p.damping = 2 * omega1;
  ElasticSolver<2, Policies> s(set, p);
  const auto tip = scenes::select(set, [&](const Vec<2>& x) { return x[0] > length - l0; });
  for (const auto i : scenes::select(set, [](const Vec<2>& x) { return x[0] < 0; })) s.clamp(i);
  for (const auto i : tip) s.external_force()[i] = Vec<2>(0, -load / static_cast<double>(tip.size()));
  relax(s, omega1);
  double deflection = 0;
  for (const auto i : tip) deflection -= (s.particles().positions()[i] - s.reference_positions()[i])[1];
  deflection /= static_cast<double>(tip.size());
  const double xp = length - l0 / 2, shear_modulus = e / (2 * (1 + nu));
  const double timoshenko = load * xp * xp * xp / (3 * e * inertia) + load * xp / (5.0 / 6.0 * shear_modulus * h);
  return {deflection, timoshenko};
}

// Simply supported beam of the paper's case 02 (span 0.18 m, h = 0.038 m, E = 270.084 MPa,
// nu = 0.3, ice 917 kg/m3), plane stress, l0 = 2 mm, roller supports under the bottom row at
// x = +-L/2, load P at mid-span on the top row (1/4, 1/2, 1/4 over three particles). Returns
// {simulated, Timoshenko} stiffness P/delta, delta the mid-height deflection at mid-span
// relative to mid-height over the supports.
template <class Policies>
std::pair<double, double> run_simply_supported() {
  const double h = 0.038, span = 0.18, l0 = 0.002, e = 270.084e6, nu = 0.3, rho = 917, load = 1000;
  auto set = scenes::material_block<2>(Vec<2>(-0.101, 0), Vec<2>(0.101, h), l0);
  SolidParameters<2> p;
  p.l0 = l0;
  p.density = rho;
  p.youngs_modulus = e;
  p.poisson_ratio = nu;
  p.plane_model = PlaneModel::plane_stress;
  const double inertia = h * h * h / 12;
  const double omega1 = std::pow(M_PI / span, 2) * std::sqrt(e * inertia / (rho * h));
  p.damping = 2 * omega1;
  ElasticSolver<2, Policies> s(set, p);
  auto near = [&](const Vec<2>& x, double cx, double cy) { return std::abs(x[0] - cx) < 0.1 * l0 && std::abs(x[1] - cy) < 0.1 * l0; };
  std::size_t mid = 0, left = 0, right = 0;
  for (std::size_t i = 0; i < set.size(); ++i) {
    const Vec<2>& x = set.positions()[i];
    if (near(x, -span / 2, l0 / 2) || near(x, span / 2, l0 / 2)) s.support(i, Vec<2>(0, 1));
    if (near(x, 0, l0 / 2)) s.support(i, Vec<2>(1, 0));  // symmetry line: no rigid sliding
    if (near(x, 0, h - l0 / 2)) s.external_force()[i] = Vec<2>(0, -load / 2);
    if (near(x, -l0, h - l0 / 2) || near(x, l0, h - l0 / 2)) s.external_force()[i] = Vec<2>(0, -load / 4);
    if (near(x, 0, h / 2)) mid = i;
    if (near(x, -span / 2, h / 2)) left = i;
    if (near(x, span / 2, h / 2)) right = i;
  }
  relax(s, omega1);
  auto v = [&](std::size_t i) { return (s.particles().positions()[i] - s.reference_positions()[i])[1]; };
  const double deflection = 0.5 * (v(left) + v(right)) - v(mid);
  const double shear_modulus = e / (2 * (1 + nu));
  const double timoshenko = span * span * span / (48 * e * inertia) + span / (4 * 5.0 / 6.0 * shear_modulus * h);
  return {load / deflection, 1 / timoshenko};
}

// A free block spun through 90 degrees at a rate whose centrifugal stress rho w^2 R^2 is far
// below the 1e-6 E bound. Returns the largest |sigma| / E at the end.
template <class Policies>
double run_rigid_spin() {
  const double l0 = 0.01, omega = 3.0, e = 1e9;
  auto set = scenes::material_block<2>(Vec<2>(-0.05, -0.05), Vec<2>(0.05, 0.05), l0);
  for (std::size_t i = 0; i < set.size(); ++i) {
    const Vec<2>& x = set.positions()[i];
    set.velocities()[i] = Vec<2>(-omega * x[1], omega * x[0]) + Vec<2>(0.5, 0.2);
  }
  SolidParameters<2> p;
  p.l0 = l0;
  p.density = 1000;
  p.youngs_modulus = e;
  p.poisson_ratio = 0.3;
  ElasticSolver<2, Policies> s(set, p);
  if constexpr (std::is_same_v<typename Policies::stress_model, HwangModel<2>>)
    for (std::size_t i = 0; i < set.size(); ++i) s.stress_model().spin(i)[0] = omega;
  s.advance_to(M_PI / 2 / omega);
  double worst = 0;
  for (const auto& sigma : s.stresses()) worst = std::max(worst, sigma.norm() / e);
  return worst;
}

}  // namespace

TEST_SUITE("verification.solid") {

TEST_CASE("oscillating plate 2D at H/l0 = 10 over ten periods") {
  const double reference = scenes::OscillatingPlate{}.period(true);
  const auto r = run_plate<2, SolidDefaults<2>>(10, 10.0);
  MESSAGE("plate 2D H/l0=10 (" << r.particles << " particles): T = " << r.period << " s vs " << reference
                                << " s (" << 100 * (r.period / reference - 1) << " %), energy drift "
                                << 100 * r.energy_drift << " %, tip amplitude " << r.amplitude << " m");
  // 3 %: the analytic period plus the first-order clamp error at H/l0 = 10 (convergence study:
  // +6.2, +2.8, +1.5 % at H/l0 = 5, 10, 20; docs/validation/solid.md).
  CHECK(test::within_relative(r.period, reference, 0.03));
  // 1 %: energy conservation. Velocity Verlet is symplectic and the forces are the exact gradient
  // of the discrete energy, so only the integrator's bounded error remains (measured <= 1e-6).
  CHECK(r.energy_drift <= 0.01);
}

TEST_CASE("oscillating plate 3D bar at coarse resolution") {
  // The 3D bar obeys the same formula without the plane-strain factor 1/(1 - nu^2).
  const double reference = scenes::OscillatingPlate{}.period(false);
  const auto r = run_plate<3, SolidDefaults<3>>(6, 1.6);
  MESSAGE("bar 3D H/l0=6 (" << r.particles << " particles): T = " << r.period << " s vs " << reference << " s ("
                            << 100 * (r.period / reference - 1) << " %)");
  // 5 %: the analytic period, with more room than the 2D plate's 3 % at this coarse H/l0 = 6 (the
  // 2D clamp error is +6.2 % at 5 and +2.8 % at 10 particles across); measured +4.45 %.
  CHECK(test::within_relative(r.period, reference, 0.05));
}

TEST_CASE("cantilever under a tip load against Timoshenko beam theory") {
  // h/l0 = 20: the error converges at first order from the clamp (the kinematic constraint acts
  // at the last clamped particle's centre, l0/2 behind the clamp face): 10.1 % at h/l0 = 5,
  // 3.8 % at 10, 1.5 % at 20 (validation.solid; docs/validation/solid.md).
  const auto [sim, theory] = run_cantilever<SolidDefaults<2>>(20);
  MESSAGE("cantilever L/h=10 h/l0=20 plane stress: tip deflection " << sim << " m vs Timoshenko " << theory << " m ("
                                                            << 100 * (sim / theory - 1) << " %)");
  CHECK(test::within_relative(sim, theory, 0.03));  // 3 %: Timoshenko, above the +1.5 % clamp error at h/l0 = 20
}

TEST_CASE("simply supported beam of case 02 against Timoshenko beam theory") {
  const auto [sim, theory] = run_simply_supported<SolidDefaults<2>>();
  MESSAGE("simply supported case 02 plane stress: P/delta " << sim << " N/m/m vs Timoshenko " << theory << " ("
                                                            << 100 * (sim / theory - 1) << " %)");
  // 5 %: Timoshenko's stiffness with shear (kappa = 5/6), the accuracy expected of the method for
  // this deep beam (L/h = 4.7) on point supports under a point load; measured +1.65 %.
  CHECK(test::within_relative(sim, theory, 0.05));
}

TEST_CASE("rigid spin through 90 degrees stays unstressed") {
  const double worst = run_rigid_spin<SolidDefaults<2>>();
  MESSAGE("rigid spin: max |sigma|/E = " << worst);
  // Rigid motion is stress-free. 1e-6 E is 20-50 times the true centrifugal stress rho omega^2 R^2
  // and far below the order-E stress of a rotation read as strain; measured 2.6e-8 E.
  CHECK(worst < 1e-6);
}

}

// Long runs: resolution study and the paper's model side by side (CTest label "validation").
TEST_SUITE("validation.solid") {

TEST_CASE("oscillating plate 2D converges with H/l0 = 5, 10, 20") {
  const double reference = scenes::OscillatingPlate{}.period(true);
  std::vector<double> error;
  for (const int layers : {5, 10, 20}) {
    const auto r = run_plate<2, SolidDefaults<2>>(layers, 1.6);
    error.push_back(std::abs(r.period / reference - 1));
    MESSAGE("plate 2D H/l0=" << layers << ": T = " << r.period << " s, error " << 100 * error.back() << " %");
  }
  CHECK(error[1] < error[0]);
  CHECK(error[2] < error[1]);
}

TEST_CASE("cantilever converges with h/l0 = 5, 10, 20") {
  for (const int layers : {5, 10, 20}) {
    const auto [sim, theory] = run_cantilever<SolidDefaults<2>>(layers);
    MESSAGE("cantilever h/l0=" << layers << ": error " << 100 * (sim / theory - 1) << " %");
  }
}

TEST_CASE("paper model and corrected model side by side") {
  const double reference = scenes::OscillatingPlate{}.period(true);
  const auto plate_c = run_plate<2, SolidDefaults<2>>(10, 10.0);
  const auto plate_p = run_plate<2, PaperSolidPolicies<2>>(10, 10.0);
  const auto bar_c = run_plate<3, SolidDefaults<3>>(6, 1.6);
  const auto bar_p = run_plate<3, PaperSolidPolicies<3>>(6, 1.6);
  const auto cant_c = run_cantilever<SolidDefaults<2>>(20);
  const auto cant_p = run_cantilever<PaperSolidPolicies<2>>(20);
  const auto ss_c = run_simply_supported<SolidDefaults<2>>();
  const auto ss_p = run_simply_supported<PaperSolidPolicies<2>>();
  const double spin_c = run_rigid_spin<SolidDefaults<2>>();
  const double spin_p = run_rigid_spin<PaperSolidPolicies<2>>();
  const double bar_ref = scenes::OscillatingPlate{}.period(false);
  char table[2048];
  std::snprintf(table, sizeof table,
                "\n| check | corrected TL (default) | paper eqs 16-17 |\n|---|---|---|\n"
                "| plate 2D period error, H/l0=10 | %+.2f %% | %+.2f %% |\n"
                "| plate 2D energy drift, 10 periods | %.1e %% | %.1e %% |\n"
                "| bar 3D period error, H/l0=6 | %+.2f %% | %+.2f %% |\n"
                "| cantilever tip deflection error, h/l0=20 | %+.2f %% | %+.2f %% |\n"
                "| simply supported stiffness error | %+.2f %% | %+.2f %% |\n"
                "| rigid spin max |sigma|/E | %.1e | %.1e |\n",
                100 * (plate_c.period / reference - 1), 100 * (plate_p.period / reference - 1),
                100 * plate_c.energy_drift, 100 * plate_p.energy_drift, 100 * (bar_c.period / bar_ref - 1),
                100 * (bar_p.period / bar_ref - 1), 100 * (cant_c.first / cant_c.second - 1),
                100 * (cant_p.first / cant_p.second - 1), 100 * (ss_c.first / ss_c.second - 1),
                100 * (ss_p.first / ss_p.second - 1), spin_c, spin_p);
  MESSAGE(table);
  // The corrected model is the default because it is the better one: its cantilever error may exceed
  // the paper model's by at most 0.5 %, and its energy drift may not exceed the paper model's
  // (measured +1.53 against +4.75 %, and <= 1e-6 against 11 %; docs/validation/solid.md).
  CHECK(std::abs(cant_c.first / cant_c.second - 1) <= std::abs(cant_p.first / cant_p.second - 1) + 0.005);
  CHECK(plate_c.energy_drift <= plate_p.energy_drift);
}

}
