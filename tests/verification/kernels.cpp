// SPDX-License-Identifier: BSD-3-Clause
// Verification of the MPS operators against analytic fields (docs/theory.md, section 1).
// Tolerances: "round-off" checks use 1e-10 relative to the field's scale: each sum has at most a
// few hundred terms of size O(1) in units of the field, so double rounding stays below ~1e-13;
// 1e-10 leaves room for the cancellation in phi_j - phi_i and still fails on any O(l0) error.
#include <doctest/doctest.h>

#include <cmath>
#include <cstdio>
#include <vector>

#include "mpsfsi/core/cell_list_search.hpp"
#include "mpsfsi/kernels/divergence.hpp"
#include "mpsfsi/kernels/gradient.hpp"
#include "mpsfsi/kernels/gradient_correction.hpp"
#include "mpsfsi/kernels/laplacian.hpp"
#include "mpsfsi/kernels/lattice_constants.hpp"
#include "mpsfsi/kernels/number_density.hpp"
#include "mpsfsi/scenes/lattice.hpp"
#include "support/tolerance.hpp"

using namespace mpsfsi;

namespace {

// A lattice of side `side` (m) with spacing l0 starting at an offset from the origin, optionally
// jittered, its neighbour list for radius `radius`, and the particles at least `radius` from
// every face (full neighbourhoods).
template <int Dim>
struct Lattice {
  ParticleSet<Dim> set;
  NeighborList list;
  std::vector<std::size_t> interior;

  Lattice(double side, double l0, double radius, double jitter_fraction, bool distances = true) {
    const Vec<Dim> lower = Vec<Dim>::Constant(0.3);
    const Vec<Dim> upper = lower + Vec<Dim>::Constant(side);
    set = scenes::lattice_box<Dim>(lower, upper, l0);
    if (jitter_fraction > 0) scenes::jitter(set, jitter_fraction * l0, 2024);
    CellListSearch<Dim> search(radius);
    search.build(set.positions());
    QueryOptions opt;
    opt.store_distances = distances;
    search.self_query(set.positions(), list, opt);
    const double margin = radius + 0.5 * l0;
    for (std::size_t i = 0; i < set.size(); ++i) {
      const auto& x = set.positions()[i];
      if (((x - lower).array() > margin).all() && ((upper - x).array() > margin).all()) interior.push_back(i);
    }
  }
};

template <int Dim>
Vec<Dim> slope() {
  Vec<Dim> b;
  b[0] = 1.7;
  b[1] = -0.6;
  if constexpr (Dim == 3) b[2] = 2.3;
  return b;
}

}  // namespace

TEST_SUITE("verification.kernels") {

TEST_CASE_TEMPLATE("verification.kernels: number density of a full lattice neighbourhood is n0", V, Vec<2>, Vec<3>) {
  constexpr int Dim = static_cast<int>(V::RowsAtCompileTime);
  const double l0 = 0.01;
  for (double ratio : {2.1, 3.1, 4.0}) {
    const double re = ratio * l0;
    Lattice<Dim> lat(Dim == 2 ? 0.2 : 0.12, l0, re, 0.0);
    REQUIRE(!lat.interior.empty());
    std::vector<double> n, nw;
    number_density<KoshizukaWeight>(lat.set.positions(), lat.list, re, n);
    number_density<WendlandC2Weight>(lat.set.positions(), lat.list, re, nw);
    const double n0 = ideal_lattice_constants<Dim, KoshizukaWeight>(l0, re).n0;
    const double n0w = ideal_lattice_constants<Dim, WendlandC2Weight>(l0, re).n0;
    for (std::size_t i : lat.interior) {
      CHECK(test::within_relative(n[i], n0, 1e-12));
      CHECK(test::within_relative(nw[i], n0w, 1e-12));
    }
  }
}

TEST_CASE_TEMPLATE("verification.kernels: standard gradient and divergence are exact for linear fields on a perfect lattice",
                   V, Vec<2>, Vec<3>) {
  constexpr int Dim = static_cast<int>(V::RowsAtCompileTime);
  const double l0 = 0.01, re = 2.1 * l0;
  Lattice<Dim> lat(Dim == 2 ? 0.2 : 0.1, l0, re, 0.0);
  const auto c = ideal_lattice_constants<Dim, KoshizukaWeight>(l0, re);
  const Vec<Dim> b = slope<Dim>();
  std::vector<double> phi(lat.set.size());
  VecArray<Dim> u(lat.set.size());
  Mat<Dim> grad_u = Mat<Dim>::Identity() * 0.4;
  grad_u(0, 1) = 1.3;
  for (std::size_t i = 0; i < phi.size(); ++i) {
    phi[i] = 5.0 + b.dot(lat.set.positions()[i]);
    u[i] = grad_u * lat.set.positions()[i];
  }
  NoGradientCorrection<Dim> none;
  VecArray<Dim> g;
  std::vector<double> div;
  gradient<KoshizukaWeight>(lat.set.positions(), lat.list, phi, c, none, g);
  divergence<KoshizukaWeight>(lat.set.positions(), lat.list, u, c, none, div);
  double worst_g = 0, worst_d = 0;
  for (std::size_t i : lat.interior) {
    worst_g = std::max(worst_g, (g[i] - b).norm() / b.norm());
    worst_d = std::max(worst_d, std::abs(div[i] - grad_u.trace()) / grad_u.norm());
  }
  MESSAGE("standard operators on a perfect lattice, worst relative error: gradient " << worst_g
                                                                                     << ", divergence " << worst_d);
  CHECK(worst_g < 1e-10);
  CHECK(worst_d < 1e-10);
}

TEST_CASE_TEMPLATE("verification.kernels: corrected gradient and divergence are exact for linear fields on a jittered lattice",
                   V, Vec<2>, Vec<3>) {
  constexpr int Dim = static_cast<int>(V::RowsAtCompileTime);
  const double l0 = 0.01, re = 2.1 * l0;
  Lattice<Dim> lat(Dim == 2 ? 0.2 : 0.1, l0, re, 0.2);
  const auto c = ideal_lattice_constants<Dim, KoshizukaWeight>(l0, re);
  const Vec<Dim> b = slope<Dim>();
  std::vector<double> phi(lat.set.size());
  VecArray<Dim> u(lat.set.size());
  Mat<Dim> grad_u = Mat<Dim>::Identity() * -0.7;
  grad_u(1, 0) = 0.9;
  for (std::size_t i = 0; i < phi.size(); ++i) {
    phi[i] = -2.0 + b.dot(lat.set.positions()[i]);
    u[i] = grad_u * lat.set.positions()[i];
  }
  KhayyerGotohCorrection<Dim> kg;
  kg.template update<KoshizukaWeight>(lat.set.positions(), lat.list, c);
  NoGradientCorrection<Dim> none;
  VecArray<Dim> g, g_std;
  std::vector<double> div;
  gradient<KoshizukaWeight>(lat.set.positions(), lat.list, phi, c, kg, g);
  gradient<KoshizukaWeight>(lat.set.positions(), lat.list, phi, c, none, g_std);
  divergence<KoshizukaWeight>(lat.set.positions(), lat.list, u, c, kg, div);
  double worst = 0, worst_std = 0, worst_div = 0;
  for (std::size_t i : lat.interior) {
    REQUIRE(kg.is_corrected(i));
    worst = std::max(worst, (g[i] - b).norm() / b.norm());
    worst_std = std::max(worst_std, (g_std[i] - b).norm() / b.norm());
    worst_div = std::max(worst_div, std::abs(div[i] - grad_u.trace()) / grad_u.norm());
  }
  MESSAGE("jittered lattice (0.2 l0), worst relative gradient error: corrected " << worst << ", standard "
                                                                                 << worst_std);
  CHECK(worst < 1e-10);
  CHECK(worst_div < 1e-10);
  // The standard operator is not exact off the lattice: this is what the correction is for.
  CHECK(worst_std > 1e-3);
}

TEST_CASE("verification.kernels: correction falls back to the standard operator where the moment matrix is singular") {
  // Three particles on a line: the moment matrix has rank 1.
  VecArray<2> x = {Vec<2>(0, 0), Vec<2>(1, 0), Vec<2>(2, 0)};
  CellListSearch<2> search(2.1);
  search.build(x);
  NeighborList list;
  search.self_query(x, list);
  const auto c = ideal_lattice_constants<2, KoshizukaWeight>(1.0, 2.1);
  KhayyerGotohCorrection<2> kg;
  kg.update<KoshizukaWeight>(x, list, c);
  for (std::size_t i = 0; i < 3; ++i) {
    CHECK_FALSE(kg.is_corrected(i));
    CHECK(kg.apply(i, Vec<2>(1, 1)) == Vec<2>(2, 2));
  }
}

TEST_CASE_TEMPLATE("verification.kernels: Laplacian is exact for quadratic fields on a perfect lattice", V, Vec<2>, Vec<3>) {
  constexpr int Dim = static_cast<int>(V::RowsAtCompileTime);
  const double l0 = 0.01;
  for (double ratio : {2.1, 3.1, 4.0}) {
    const double re = ratio * l0;
    Lattice<Dim> lat(Dim == 2 ? 0.2 : 0.12, l0, re, 0.0);
    const auto c = ideal_lattice_constants<Dim, KoshizukaWeight>(l0, re);
    // phi = x^2 + 3 y^2 (+ 2 z^2) + x y: lap = 2 + 6 (+ 4).
    std::vector<double> phi(lat.set.size());
    for (std::size_t i = 0; i < phi.size(); ++i) {
      const auto& p = lat.set.positions()[i];
      phi[i] = p[0] * p[0] + 3 * p[1] * p[1] + p[0] * p[1] + (Dim == 3 ? 2 * p[Dim - 1] * p[Dim - 1] : 0.0);
    }
    const double exact = Dim == 3 ? 12.0 : 8.0;
    std::vector<double> lap;
    laplacian<KoshizukaWeight>(lat.set.positions(), lat.list, phi, c, lap);
    double worst = 0;
    for (std::size_t i : lat.interior) worst = std::max(worst, std::abs(lap[i] - exact) / exact);
    // Round-off: phi_j - phi_i cancels a linear part ~ (x/l0) = 50 times the quadratic part.
    CHECK(worst < 1e-8);
  }
}

TEST_CASE_TEMPLATE("verification.kernels: Laplacian converges at second order for a smooth field", V, Vec<2>, Vec<3>) {
  // phi = sin(k x) sin(k y) (sin(k z)): lap = -d k^2 phi. On a lattice the MPS Laplacian's error
  // is O(l0^2) for fixed re/l0 (the odd moments cancel, the fourth moment remains); the observed
  // order between successive halvings of l0 must be 2 within 10 %.
  constexpr int Dim = static_cast<int>(V::RowsAtCompileTime);
  const double k = 2.0;
  const double side = 1.0;
  std::vector<double> spacings = Dim == 2 ? std::vector<double>{0.04, 0.02, 0.01} : std::vector<double>{0.05, 0.025};
  std::vector<double> errors;
  for (double l0 : spacings) {
    const double re = 3.1 * l0;
    Lattice<Dim> lat(side, l0, re, 0.0, false);
    const auto c = ideal_lattice_constants<Dim, KoshizukaWeight>(l0, re);
    std::vector<double> phi(lat.set.size()), exact(lat.set.size());
    for (std::size_t i = 0; i < phi.size(); ++i) {
      const auto& p = lat.set.positions()[i];
      double v = 1;
      for (int a = 0; a < Dim; ++a) v *= std::sin(k * p[a]);
      phi[i] = v;
      exact[i] = -Dim * k * k * v;
    }
    std::vector<double> lap;
    laplacian<KoshizukaWeight>(lat.set.positions(), lat.list, phi, c, lap);
    double err = 0;
    for (std::size_t i : lat.interior) err = std::max(err, std::abs(lap[i] - exact[i]));
    errors.push_back(err / (Dim * k * k));
  }
  for (std::size_t m = 1; m < errors.size(); ++m) {
    const double order = std::log(errors[m - 1] / errors[m]) / std::log(spacings[m - 1] / spacings[m]);
    MESSAGE("Laplacian, l0 = " << spacings[m] << ": max relative error " << errors[m] << ", observed order " << order);
    CHECK(test::within_relative(order, 2.0, 0.1));
  }
}

}  // TEST_SUITE
