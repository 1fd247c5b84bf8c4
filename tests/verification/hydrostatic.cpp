// SPDX-License-Identifier: BSD-3-Clause
// Hydrostatic tank: a water column at rest in an open tank, against rho g (H - y).
#include <doctest/doctest.h>

#include <cmath>
#include <cstdio>

#include "mpsfsi/fluid/fluid_solver.hpp"
#include "mpsfsi/scenes/tank.hpp"
#include "support/tolerance.hpp"

using namespace mpsfsi;

namespace {

template <int Dim, class Policies = FluidDefaults<Dim>>
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
  FluidSolver<Dim, Policies> solver(std::move(set), p);

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
  // The pressure along the depth: time-averaged pressures averaged over layers one spacing
  // thick, against rho g (H - y) at the layer's mean height. The worst single particle is
  // reported too.
  const auto layers = static_cast<std::size_t>(std::llround(depth / l0));
  std::vector<double> layer_p(layers, 0.0), layer_y(layers, 0.0), layer_n(layers, 0.0);
  double worst_particle = 0, volume_ratio = 0;
  std::size_t fluid = 0, escaped = 0;
  for (std::size_t i = 0; i < ps.size(); ++i) {
    if (ps.kinds()[i] != ParticleKind::fluid) continue;
    ++fluid;
    const Vec<Dim>& x = ps.positions()[i];
    bool inside = x[Dim - 1] > 0 && x[Dim - 1] < 1.5 * depth;
    for (int k = 0; k < Dim - 1; ++k) inside = inside && x[k] > 0 && x[k] < width;
    escaped += inside ? 0 : 1;
    const double y = x[Dim - 1];
    if (y > 0.8 * depth || y < 0) continue;
    const double p_mean = mean[i] / samples;
    worst_particle = std::max(worst_particle, std::abs(p_mean - rho_g * (depth - y)) / (rho_g * depth));
    const auto layer = std::min(layers - 1, static_cast<std::size_t>(y / l0));
    layer_p[layer] += p_mean;
    layer_y[layer] += y;
    layer_n[layer] += 1;
  }
  double worst = 0;
  for (std::size_t l = 0; l < layers; ++l) {
    if (layer_n[l] == 0) continue;
    const double y = layer_y[l] / layer_n[l];
    worst = std::max(worst, std::abs(layer_p[l] / layer_n[l] - rho_g * (depth - y)) / (rho_g * depth));
  }
  // Volume: the column height in a tank of fixed width, from the highest particle of each
  // lateral column (half a spacing below the surface). n0 / <n> over particles with a full neighbourhood is reported too, but
  // disorder alone shifts n by a per cent or so, so it is no measure of volume to assert on.
  const double margin = p.re_laplacian() + l0;
  double n_sum = 0;
  std::size_t n_count = 0;
  // Highest particle in each lateral column of width l0; their mean + l0/2 is the surface.
  const auto columns = static_cast<std::size_t>(std::llround(width / l0));
  std::vector<double> column_top(Dim == 3 ? columns * columns : columns, -1.0);
  for (std::size_t i = 0; i < ps.size(); ++i) {
    if (ps.kinds()[i] != ParticleKind::fluid) continue;
    const Vec<Dim>& x = ps.positions()[i];
    bool interior = x[Dim - 1] > margin && x[Dim - 1] < depth - margin;
    for (int k = 0; k < Dim - 1; ++k) interior = interior && x[k] > margin && x[k] < width - margin;
    if (interior) {
      n_sum += solver.number_density_field()[i];
      ++n_count;
    }
    std::size_t c = 0;
    for (int k = Dim - 2; k >= 0; --k)
      c = c * columns + std::min(columns - 1, static_cast<std::size_t>(std::max(0.0, x[k] / l0)));
    column_top[c] = std::max(column_top[c], x[Dim - 1]);
  }
  volume_ratio = solver.density_constants().n0 / (n_sum / n_count);
  double top_sum = 0;
  for (double t : column_top) top_sum += t;
  const double surface_height = top_sum / static_cast<double>(column_top.size()) + 0.5 * l0;
  MESSAGE(Dim << "D hydrostatic tank, " << fluid << " fluid particles, " << solver.step_count()
              << " steps: pressure profile, worst layer |<P> - rho g (H - y)| / (rho g H) over the lower 80 % = "
              << worst << " (worst single particle " << worst_particle << "), volume ratio n0/<n> " << volume_ratio
              << ", mean surface height / H " << surface_height / depth
              << ", last PPE " << solver.last_solve().iterations << " iterations");
  CHECK(escaped == 0);
  CHECK(worst < 0.03);
  // Volume: the column height in a tank of fixed width, within 1 %: an incompressible column keeps
  // its height, and 1 % of H is 0.4 l0 (2D) and 0.3 l0 (3D) (measured 1.005 H and 0.993 H).
  CHECK(test::within_relative(surface_height, depth, 0.01));
}

}  // namespace

TEST_SUITE("verification.fluid") {

TEST_CASE("verification.fluid: hydrostatic tank 2D") {
  // Tolerance 3 % of rho g H: the analytic pressure, with room for the known error sources. P = 0
  // is imposed on the surface particles, half a spacing below the true surface (l0 / (2 H) = 1.25 %
  // here), and the time average leaves some pressure noise. Measured 0.58 % (docs/validation/fluid.md).
  run_hydrostatic<2>(0.2, 0.2, 0.005, 1.0, 0.5, 5e-4);
}

TEST_CASE("verification.fluid: hydrostatic tank 3D") {
  // Same tolerances; 30 layers deep so that the surface offset l0 / (2 H) is 1.7 % (measured 2.0 %).
  run_hydrostatic<3>(0.08, 0.24, 0.008, 1.0, 0.5, 1e-3);
}

}  // TEST_SUITE
