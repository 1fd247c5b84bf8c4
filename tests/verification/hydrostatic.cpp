// SPDX-License-Identifier: BSD-3-Clause
// Hydrostatic tank (issue 3, verification 1): a water column at rest in an open tank.
#include <doctest/doctest.h>

#include <cmath>
#include <cstdio>

#include "mpsfsi/fluid/fluid_solver.hpp"
#include "mpsfsi/scenes/tank.hpp"

using namespace mpsfsi;

namespace {

template <int Dim>
void run_hydrostatic(double width, double depth, double l0, double settle, double average, double dt) {
  ParticleSet<Dim> set;
  Vec<Dim> tank = Vec<Dim>::Constant(width);
  tank[Dim - 1] = 1.5 * depth;
  Vec<Dim> water = Vec<Dim>::Constant(width);
  water[Dim - 1] = depth;
  scenes::add_block<Dim, double>(set, Vec<Dim>::Zero(), water, l0, ParticleKind::fluid);
  scenes::add_tank<Dim, double>(set, tank, l0);
  FluidParameters<Dim> p;
  p.l0 = l0;
  p.dt = dt;
  FluidSolver<Dim> solver(std::move(set), p);

  solver.advance_to(settle);
  // Time-average the pressure of every fluid particle over `average` seconds.
  const auto& ps = solver.particles();
  std::vector<double> mean(ps.size(), 0.0);
  int samples = 0;
  while (solver.time() < settle + average - 1e-9) {
    solver.step();
    for (std::size_t i = 0; i < ps.size(); ++i) mean[i] += solver.pressure()[i];
    ++samples;
  }
  const double rho_g = p.density * p.gravity.norm();
  double worst = 0, volume_ratio = 0;
  std::size_t fluid = 0, escaped = 0, checked = 0;
  for (std::size_t i = 0; i < ps.size(); ++i) {
    if (ps.kinds()[i] != ParticleKind::fluid) continue;
    ++fluid;
    const Vec<Dim>& x = ps.positions()[i];
    bool inside = x[Dim - 1] > 0 && x[Dim - 1] < 1.5 * depth;
    for (int k = 0; k < Dim - 1; ++k) inside = inside && x[k] > 0 && x[k] < width;
    escaped += inside ? 0 : 1;
    // Initial position tells the depth the particle belongs to; the column barely moves.
    const double y = x[Dim - 1];
    if (y > 0.8 * depth) continue;
    const double exact = rho_g * (depth - y);
    worst = std::max(worst, std::abs(mean[i] / samples - exact) / (rho_g * depth));
    ++checked;
  }
  // Volume: the highest fluid particle sets the free surface, half a spacing above it.
  double top = 0;
  for (std::size_t i = 0; i < ps.size(); ++i)
    if (ps.kinds()[i] == ParticleKind::fluid) top = std::max(top, ps.positions()[i][Dim - 1]);
  volume_ratio = (top + 0.5 * l0) / depth;
  MESSAGE(Dim << "D hydrostatic tank, " << fluid << " fluid particles, " << solver.step_count()
              << " steps: worst |<P> - rho g (H - y)| / (rho g H) over the lower 80 % = " << worst
              << " (" << checked << " particles), column height ratio " << volume_ratio
              << ", last PPE " << solver.last_solve().iterations << " iterations");
  CHECK(escaped == 0);
  CHECK(worst < 0.03);
  CHECK(volume_ratio == doctest::Approx(1.0).epsilon(0.01));
}

}  // namespace

TEST_SUITE("verification.fluid") {

TEST_CASE("verification.fluid: hydrostatic tank 2D") {
  // Tolerance 3 % of rho g H (issue 3). Expected error sources: P = 0 is imposed on the surface
  // particles, half a spacing below the true surface (l0 / (2 H) = 1.25 % here), and the
  // residual pressure noise of the time average.
  run_hydrostatic<2>(0.2, 0.2, 0.005, 1.0, 0.5, 5e-4);
}

}  // TEST_SUITE
