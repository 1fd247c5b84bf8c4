// SPDX-License-Identifier: BSD-3-Clause
// The policies docs/extending.md shows, compiled and checked: each region between
// "// [snippet: name]" and "// [end snippet]" stands word for word in that page (CTest
// extending.snippets_in_docs), so the page cannot drift from code that builds and works.
#include <doctest/doctest.h>

#include <cmath>
#include <limits>

#include <mpsfsi/mpsfsi.hpp>

#include "support/ice.hpp"

namespace {

// [snippet: weight]
// A smooth weight w(r) = (1 - r/re)^2 for r < re: bounded, non-singular, zero slope at re.
struct QuadraticWeight {
  template <class Scalar>
  static Scalar value(Scalar r, Scalar re) {
    if (!(r < re)) return Scalar(0);
    const Scalar q = Scalar(1) - r / re;
    return q * q;
  }
};

struct QuadraticFluid : mpsfsi::FluidDefaults<2> {
  using weight = QuadraticWeight;  // every other member stays the default
};
// [end snippet]

// [snippet: linear_solver]
// SSOR-CG first; where it does not converge, the same system again with incomplete-Cholesky CG.
class SsorWithFallback {
 public:
  mpsfsi::SolveReport solve(const mpsfsi::PpeMatrix& a, const mpsfsi::PpeVector& b, mpsfsi::PpeVector& x,
                            double tolerance, int max_iterations) {
    const mpsfsi::PpeVector start = x;  // the warm start, kept for the second attempt
    const mpsfsi::SolveReport first = ssor_.solve(a, b, x, tolerance, max_iterations);
    if (first.converged) return first;
    x = start;
    return fallback_.solve(a, b, x, tolerance, max_iterations);
  }

 private:
  mpsfsi::SsorCg ssor_;
  mpsfsi::IncompleteCholeskyCg fallback_;
};

struct RobustFluid : mpsfsi::FluidDefaults<2> {
  using linear_solver = SsorWithFallback;
};
// [end snippet]

// [snippet: failure]
// Ice whose cracks can only open across x (say, a sheet with vertical columnar grains): the
// normal stress along x against sigma_f, the crack plane always normal to x.
struct TensionAlongX {
  static constexpr bool enabled = true;
  template <int Dim, class Scalar>
  static Scalar principal(const mpsfsi::Mat<Dim, Scalar>& sigma, mpsfsi::Vec<Dim, Scalar>& direction) {
    direction = mpsfsi::Vec<Dim, Scalar>::UnitX();
    return sigma(0, 0);
  }
};

template <int Dim>
struct ColumnarIce : mpsfsi::SolidDefaults<Dim> {
  using failure = TensionAlongX;
};
// [end snippet]

// [snippet: failure-model]
// A maximum principal strain criterion with its parameters: the strain from the stress by
// Hooke's law (plane stress or 3D), its largest principal value against a critical strain, which
// the model gives every particle as its strength.
struct MaxPrincipalStrain {
  static constexpr bool enabled = true;
  double youngs_modulus = 0, poisson_ratio = 0, critical_strain = 0;

  template <int Dim, class Scalar>
  Scalar principal(const mpsfsi::Mat<Dim, Scalar>& sigma, mpsfsi::Vec<Dim, Scalar>& direction) const {
    const Scalar nu = poisson_ratio;
    const mpsfsi::Mat<Dim, Scalar> strain =
        ((1 + nu) * sigma - nu * sigma.trace() * mpsfsi::Mat<Dim, Scalar>::Identity()) / youngs_modulus;
    return mpsfsi::MaxPrincipalStress::principal<Dim, Scalar>(strain, direction);
  }
  void assign_strengths(const mpsfsi::StrengthSetup& setup, std::vector<double>& strength) const {
    strength.assign(setup.ids->size(), critical_strain);
  }
};

template <int Dim>
struct StrainLimitedIce : mpsfsi::SolidDefaults<Dim> {
  using failure = MaxPrincipalStrain;
};
// [end snippet]

// A small dam break for the fluid policies: a column 0.1 m square in a tank 0.2 m long,
// l0 = 1 cm, fixed step 0.5 ms.
constexpr double kSpacing = 0.01;

mpsfsi::FluidParameters<2> small_dam_break_parameters() {
  mpsfsi::FluidParameters<2> p;
  p.l0 = kSpacing;
  p.dt = 5e-4;
  return p;
}

mpsfsi::ParticleSet<2> small_dam_break() { return mpsfsi::scenes::dam_break<2>(0.1, 0.1, 0.2, 0.15, kSpacing); }

}  // namespace

TEST_SUITE("extending") {

TEST_CASE("extending: a user's weight function drives FluidSolver and the lattice constants") {
  using namespace mpsfsi;
  const double l0 = kSpacing;
  const auto p = small_dam_break_parameters();
  FluidSolver<2, QuadraticFluid> solver(small_dam_break(), p);
  const auto constants = ideal_lattice_constants<2, QuadraticWeight>(l0, p.re_density());
  // n0 of the ideal lattice with this weight: the sum over the full neighbourhood.
  double n0 = 0;
  for (int a = -3; a <= 3; ++a)
    for (int b = -3; b <= 3; ++b)
      if (a != 0 || b != 0) n0 += QuadraticWeight::value(l0 * std::hypot(a, b), p.re_density());
  CHECK(constants.n0 == doctest::Approx(n0).epsilon(1e-12));
  CHECK(solver.density_constants().n0 == doctest::Approx(n0).epsilon(1e-12));
  for (int k = 0; k < 20; ++k) solver.step();
  CHECK(solver.last_solve().converged);
  double fastest = 0;
  for (std::size_t i = 0; i < solver.particles().size(); ++i)
    fastest = std::max(fastest, solver.particles().velocities()[i].norm());
  CHECK(fastest < 1.0);  // a column 0.1 m high released for 10 ms: free fall reaches 0.1 m/s
}

TEST_CASE("extending: a user's linear solver gives the default's answer where SSOR-CG converges") {
  using namespace mpsfsi;
  const auto p = small_dam_break_parameters();
  const auto set = small_dam_break();
  FluidSolver<2> plain(set, p);
  FluidSolver<2, RobustFluid> robust(set, p);
  for (int k = 0; k < 10; ++k) {
    plain.step();
    robust.step();
  }
  REQUIRE(plain.last_solve().converged);
  for (std::size_t i = 0; i < set.size(); ++i) CHECK(robust.pressure()[i] == plain.pressure()[i]);

  // With too few iterations for SSOR-CG the fallback takes over and still converges.
  PpeMatrix a(3, 3);
  a.insert(0, 0) = 4, a.insert(0, 1) = -1, a.insert(1, 0) = -1, a.insert(1, 1) = 4;
  a.insert(1, 2) = -1, a.insert(2, 1) = -1, a.insert(2, 2) = 4;
  const PpeVector b = PpeVector::Ones(3);
  PpeVector x = PpeVector::Zero(3);
  SsorWithFallback solver;
  const SolveReport r = solver.solve(a, b, x, 1e-12, 3);
  CHECK(r.converged);
  CHECK((a * x - b).norm() < 1e-10);
}

TEST_CASE("extending: a user's failure criterion decides where and along which plane ice cracks") {
  using namespace mpsfsi;
  // A bar stretched along y only (sigma_yy > 0, sigma_xx about 0): the default criterion breaks
  // it across y, the user's never, since it reads sigma_xx alone.
  const double l0 = 0.01, strain = 2e-3;
  const auto bar = scenes::material_block<2>(Vec<2>::Zero(), Vec<2>(0.03, 0.12), l0);
  auto params = test::case02_ice<2>(l0);
  params.plane_model = PlaneModel::plane_stress;
  params.tensile_strength = 0.5 * params.youngs_modulus * strain;  // half the stretch's stress
  Mat<2> f = Mat<2>::Identity() * (1 - params.poisson_ratio * strain);
  f(1, 1) = 1 + strain;
  const auto run = [&](auto solver) {
    for (std::size_t i = 0; i < bar.size(); ++i) {
      solver.particles().positions()[i] = f * bar.positions()[i];
      if (bar.positions()[i][1] < 0.02 || bar.positions()[i][1] > 0.1) solver.clamp(i);
    }
    solver.step();
    return solver.failure_log();
  };
  const auto default_log = run(ElasticSolver<2, BrittleSolidPolicies<2>>(bar, params));
  REQUIRE(!default_log.empty());
  CHECK(std::abs(default_log.front().normal[1]) > 0.99);  // a crack across y
  CHECK(run(ElasticSolver<2, ColumnarIce<2>>(bar, params)).empty());

  // Stretched along x instead, the user's criterion breaks it with the crack plane normal to x.
  Mat<2> g = Mat<2>::Identity() * (1 - params.poisson_ratio * strain);
  g(0, 0) = 1 + strain;
  const auto wide = scenes::material_block<2>(Vec<2>::Zero(), Vec<2>(0.12, 0.03), l0);
  ElasticSolver<2, ColumnarIce<2>> s(wide, params);
  for (std::size_t i = 0; i < wide.size(); ++i) {
    s.particles().positions()[i] = g * wide.positions()[i];
    if (wide.positions()[i][0] < 0.02 || wide.positions()[i][0] > 0.1) s.clamp(i);
  }
  s.step();
  REQUIRE(!s.failure_log().empty());
  for (const auto& e : s.failure_log()) CHECK(e.normal[0] == 1.0);
}

TEST_CASE("extending: a user's failure model with parameters reads strain against its own strength") {
  using namespace mpsfsi;
  // A plane-stress bar stretched 2e-3 along y: the criterion reads that strain (to 1 %: the
  // stress model's Green strain differs from the small strain by strain / 2 = 0.1 %) and the bar
  // breaks when the critical strain is 1.5e-3, not when it is 2.5e-3.
  const double l0 = 0.01, strain = 2e-3;
  const auto bar = scenes::material_block<2>(Vec<2>::Zero(), Vec<2>(0.03, 0.12), l0);
  auto params = test::case02_ice<2>(l0);
  params.plane_model = PlaneModel::plane_stress;
  params.tensile_strength = 1e9;  // not read by this model
  Mat<2> f = Mat<2>::Identity() * (1 - params.poisson_ratio * strain);
  f(1, 1) = 1 + strain;
  const auto run = [&](double critical) {
    ElasticSolver<2, StrainLimitedIce<2>> solver(
        bar, params, {}, MaxPrincipalStrain{params.youngs_modulus, params.poisson_ratio, critical});
    for (std::size_t i = 0; i < bar.size(); ++i) {
      solver.particles().positions()[i] = f * bar.positions()[i];
      if (bar.positions()[i][1] < 0.02 || bar.positions()[i][1] > 0.1) solver.clamp(i);
    }
    CHECK(solver.strengths().front() == critical);
    solver.step();
    const std::size_t middle = scenes::select(bar, [](const Vec<2>& x) { return (x - Vec<2>(0.015, 0.065)).norm() < 0.006; })[0];
    CHECK(solver.criterion_stresses()[middle] == doctest::Approx(strain).epsilon(0.01));
    return solver.failure_log().size();
  };
  CHECK(run(1.5e-3) > 0);
  CHECK(run(2.5e-3) == 0);
}

}  // TEST_SUITE
