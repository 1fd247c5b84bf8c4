// SPDX-License-Identifier: BSD-3-Clause
#include <doctest/doctest.h>

#include <random>

#include <Eigen/Geometry>

#include "mpsfsi/core/parallel.hpp"
#include "mpsfsi/kernels/weight.hpp"
#include "mpsfsi/scenes/solid_block.hpp"
#include "mpsfsi/solid/bond_viscosity.hpp"

using namespace mpsfsi;

namespace {

// A block of 6 x 5 (x 4) particles, moved off the lattice by up to 0.2 l0; cut_fifth() cuts a
// fifth of its bonds and returns the particles at their ends.
template <int Dim>
struct DampedBlock {
  static constexpr double l0 = 0.01;
  ParticleSet<Dim> set;
  BondList<Dim> bonds;
  VecArray<Dim, double> x;

  DampedBlock() {
    Vec<Dim> upper = Vec<Dim>::Constant(0.04);
    upper[0] = 0.06;
    upper[1] = 0.05;
    set = scenes::material_block<Dim>(Vec<Dim>::Zero(), upper, l0);
    bonds.template build<KoshizukaWeight>(set.positions(), std::vector<std::int32_t>(set.size(), 0), 2.1 * l0);
    std::mt19937 rng(3);
    std::uniform_real_distribution<double> u(-1, 1);
    x = set.positions();
    for (auto& p : x)
      for (int a = 0; a < Dim; ++a) p[a] += 0.2 * l0 * u(rng);
  }

  std::vector<std::size_t> cut_fifth() {
    std::mt19937 rng(5);
    std::uniform_real_distribution<double> u(0, 1);
    std::vector<std::size_t> touched;
    for (std::size_t i = 0; i < x.size(); ++i)
      for (Offset b = bonds.begin(i); b < bonds.end(i); ++b)
        if (u(rng) < 0.2 && bonds.cut(b)) touched.insert(touched.end(), {i, static_cast<std::size_t>(bonds.neighbor(b))});
    return touched;
  }

  // The force of the definition, bond by bond: beta |r0| ((v_j - v_i) . e) e.
  VecArray<Dim, double> reference_force(const VecArray<Dim, double>& v, double coefficient) const {
    VecArray<Dim, double> f(x.size(), Vec<Dim>::Zero());
    for (std::size_t i = 0; i < x.size(); ++i)
      for (Offset b = bonds.begin(i); b < bonds.end(i); ++b) {
        if (!bonds.intact(b)) continue;
        const auto j = static_cast<std::size_t>(bonds.neighbor(b));
        const Vec<Dim> e = (x[j] - x[i]).normalized();
        f[i] += coefficient * bonds.beta(b) * bonds.r0(b).norm() * (v[j] - v[i]).dot(e) * e;
      }
    return f;
  }
};

}  // namespace

TEST_SUITE("solid") {

TEST_CASE_TEMPLATE("solid.bond_viscosity: the force of its definition; no force on rigid motion; momentum kept", T,
                   std::integral_constant<int, 2>, std::integral_constant<int, 3>) {
  constexpr int Dim = T::value;
  DampedBlock<Dim> block;
  BondViscosity<Dim> viscosity;
  viscosity.initialize(block.bonds);  // on the intact bonds, as the solver does; cut afterwards
  viscosity.bonds_changed(block.bonds, block.cut_fifth());
  REQUIRE(block.bonds.num_cut() > 0);
  const double coefficient = 3.7;
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-1, 1);

  VecArray<Dim, double> v(block.x.size());
  for (auto& w : v)
    for (int a = 0; a < Dim; ++a) w[a] = u(rng);
  const auto expect = block.reference_force(v, coefficient);
  double scale = 0;
  for (const auto& f : expect) scale = std::max(scale, f.norm());
  REQUIRE(scale > 0);
  for (const int threads : {1, 2}) {
    const int saved = parallel::max_threads();
    parallel::set_num_threads(threads);
    VecArray<Dim, double> force(block.x.size(), Vec<Dim>::Zero());
    viscosity.add(block.bonds, block.x, v, coefficient, force);
    parallel::set_num_threads(saved);
    double worst = 0;
    Vec<Dim> total = Vec<Dim>::Zero();
    for (std::size_t i = 0; i < force.size(); ++i) {
      worst = std::max(worst, (force[i] - expect[i]).norm());
      total += force[i];
    }
    CHECK(worst < 1e-13 * scale);                // round-off of the two forms
    CHECK(total.norm() < 1e-13 * scale * force.size());  // pairwise equal and opposite
  }

  // Rigid translation plus rotation: no bond stretches, no force.
  VecArray<Dim, double> rigid(block.x.size());
  for (std::size_t i = 0; i < rigid.size(); ++i) {
    const Vec<Dim>& p = block.x[i];
    if constexpr (Dim == 2) rigid[i] = Vec<2>(0.3, -0.2) + 5.0 * Vec<2>(-p[1], p[0]);
    else rigid[i] = Vec<3>(0.3, -0.2, 0.1) + Vec<3>(1.0, -2.0, 4.0).cross(p);
  }
  VecArray<Dim, double> force(block.x.size(), Vec<Dim>::Zero());
  viscosity.add(block.bonds, block.x, rigid, coefficient, force);
  double largest = 0;
  for (const auto& f : force) largest = std::max(largest, f.norm());
  CHECK(largest < 1e-12 * scale);
}

}
