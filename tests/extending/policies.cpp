// SPDX-License-Identifier: BSD-3-Clause
// The policies docs/extending.md shows, compiled and checked: each region between
// "// [snippet: name]" and "// [end snippet]" stands word for word in that page (CTest
// extending.snippets_in_docs), so the page cannot drift from code that builds and works.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>

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

template <int Dim>
struct QuadraticFluid : mpsfsi::FluidDefaults<Dim> {
  using weight = QuadraticWeight;  // every other member stays the default
};
// [end snippet]

// [snippet: gradient_correction]
// Khayyer & Gotoh's moment matrix A_i with a Tikhonov-regularised inverse,
//   C_i = (1 + d delta) (A_i + delta I)^-1,
// which is d I in a full neighbourhood (A_i = I/d) and stays bounded, by (1 + d delta) / delta,
// where A_i is near-singular: a smooth alternative to switching the correction off there.
template <int Dim>
class RegularisedCorrection {
 public:
  explicit RegularisedCorrection(double delta = 0.05) : delta_(delta) {}

  template <class Weight>
  void update(const mpsfsi::VecArray<Dim>& x, const mpsfsi::BasicNeighborList<double>& list,
              const mpsfsi::MpsConstants<double>& c) {
    matrix_.resize(x.size());
#if defined(_OPENMP)
#pragma omp parallel for schedule(static)  // update runs once per step; apply runs inside the solver's loops
#endif
    for (std::int64_t ii = 0; ii < static_cast<std::int64_t>(x.size()); ++ii) {
      const auto i = static_cast<std::size_t>(ii);
      mpsfsi::Mat<Dim> a = mpsfsi::Mat<Dim>::Zero();
      for (auto k = list.begin(i); k < list.end(i); ++k) {
        const mpsfsi::Vec<Dim> r = x[static_cast<std::size_t>(list.indices[k])] - x[i];
        const double d = r.norm();
        if (d > 0) a += Weight::value(d, c.re) / (d * d) * (r * r.transpose());
      }
      a /= c.n0;
      matrix_[i] = (1 + Dim * delta_) * (a + delta_ * mpsfsi::Mat<Dim>::Identity()).inverse();
    }
  }
  mpsfsi::Vec<Dim> apply(std::size_t i, const mpsfsi::Vec<Dim>& r) const { return matrix_[i] * r; }
  bool is_corrected(std::size_t) const { return true; }

 private:
  double delta_;
  mpsfsi::MatArray<Dim> matrix_;
};

template <int Dim>
struct RegularisedFluid : mpsfsi::FluidDefaults<Dim> {
  using gradient_correction = RegularisedCorrection<Dim>;
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

// [snippet: under_ice]
struct UnderIceFluid : mpsfsi::FluidDefaults<2> {
  using free_surface = mpsfsi::CentroidDeviationSurface<>;
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

// [snippet: coupling_scheme]
// Strong coupling by fixed-point iteration on the interface load with a constant relaxation
// factor, the scheme Aitken's dynamic factor improves on: F_{k+1} = F_k + omega (F~_k - F_k)
// until |F~_k - F_k| <= tolerance |F~_k|.
struct ConstantRelaxation {
  static constexpr bool iterative = true;  // it redoes the step, so the coupler keeps t^n
  static constexpr const char* name = "constant relaxation";
  double relaxation = 0.5, tolerance = 1e-3;
  int max_iterations = 200;

  template <class Step>
  void advance(Step& step) const {
    auto& load = step.load();
    auto& trial = step.workspace(0);
    step.solve_fluid();  // the explicit step first
    step.fluid_load(load);
    step.advance_structure(load);
    for (int k = 0; k < max_iterations; ++k) {
      step.solve_fluid();  // redone from t^n against the structure's new motion
      step.fluid_load(trial);
      double r2 = 0, f2 = 0;
      for (std::size_t s = 0; s < load.size(); ++s) {
        r2 += (trial[s] - load[s]).squaredNorm();
        f2 += trial[s].squaredNorm();
      }
      if (std::sqrt(r2) <= tolerance * std::sqrt(f2)) return;
      for (std::size_t s = 0; s < load.size(); ++s) load[s] += relaxation * (trial[s] - load[s]);
      step.advance_structure(load);
    }
    step.fail("the constant-relaxation coupling did not converge");
  }
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

template <int Dim = 2>
mpsfsi::FluidParameters<Dim> small_dam_break_parameters() {
  mpsfsi::FluidParameters<Dim> p;
  p.l0 = kSpacing;
  p.dt = 5e-4;
  return p;
}

// 3D: the column and the tank 0.04 m deep.
template <int Dim = 2>
mpsfsi::ParticleSet<Dim> small_dam_break() {
  return mpsfsi::scenes::dam_break<Dim>(0.1, 0.1, 0.2, 0.15, kSpacing, Dim == 3 ? 0.04 : 0.0);
}

// The surge front: the largest x of a fluid particle.
template <class Solver>
double surge_front(const Solver& solver) {
  double front = -std::numeric_limits<double>::infinity();
  const auto& set = solver.particles();
  for (std::size_t i = 0; i < set.size(); ++i)
    if (set.kinds()[i] == mpsfsi::ParticleKind::fluid) front = std::max(front, set.positions()[i][0]);
  return front;
}

// A coupled case per dimension, its structure clamped and loaded by the water: 2D, a water column
// 0.05 m high on a plate 0.1 m x 0.02 m (the hydrostatic-plate scene scaled down, l0 = 1 cm,
// fluid step 1 ms); 3D, the elastic-gate scene extruded across its width at l0 = 2.5 mm.
template <int Dim, class Scheme>
mpsfsi::FsiCoupler<mpsfsi::FluidSolver<Dim>, mpsfsi::ElasticSolver<Dim>, Scheme> clamped_structure_in_water(Scheme scheme) {
  using namespace mpsfsi;
  std::vector<std::size_t> clamped;
  std::size_t marker = 0;
  SolidParameters<Dim> sp;
  FluidParameters<Dim> fp;
  if constexpr (Dim == 2) {
    scenes::HydrostaticPlate scene;
    scene.span = 0.1;
    scene.water_height = 0.05;
    scene.thickness = 0.02;
    scene.youngs_modulus = 1e8;
    sp.l0 = fp.l0 = 0.01;
    fp.dt = 1e-3;
    scene.set_material(sp);
    ElasticSolver<2> plate(scene.plate_particles(sp.l0, clamped, marker), sp);
    for (auto i : clamped) plate.clamp(i);
    return FsiCoupler<FluidSolver<2>, ElasticSolver<2>, Scheme>(scene.fluid_particles(fp.l0), fp, std::move(plate), {},
                                                                scheme);
  } else {
    // The gate in a short, low, narrow tank: most of the full scene's particles are in its side
    // walls, which run the whole floor's length.
    scenes::ElasticGate scene;
    scene.water_height = 0.09;
    scene.floor_length = 0.02;
    scene.width = 0.01;
    sp.l0 = fp.l0 = 0.0025;
    scene.set_material(sp);
    sp.gravity = fp.gravity = scene.gravity_vector<3>();
    ElasticSolver<3> gate(scene.gate_particles<3>(sp.l0, clamped, marker), sp);
    for (auto i : clamped) gate.clamp(i);
    return FsiCoupler<FluidSolver<3>, ElasticSolver<3>, Scheme>(scene.fluid_particles<3>(fp.l0), fp, std::move(gate), {},
                                                                scheme);
  }
}

// A bar of ice, l0 = 1 cm, 0.12 m long along `axis` and 0.03 m across (and deep, in 3D).
constexpr double kBarSpacing = 0.01;

template <int Dim>
mpsfsi::ParticleSet<Dim> stretched_bar(int axis) {
  mpsfsi::Vec<Dim> size = mpsfsi::Vec<Dim>::Constant(0.03);
  size[axis] = 0.12;
  return mpsfsi::scenes::material_block<Dim>(mpsfsi::Vec<Dim>::Zero(), size, kBarSpacing);
}

// Places the solver's particles as the bar stretched by `strain` along `axis` with the lateral
// contraction of uniaxial stress, and clamps the 2 cm at each end, which keep the stretch.
template <class Solver, int Dim>
void stretch_and_clamp(Solver& solver, const mpsfsi::ParticleSet<Dim>& bar, int axis, double strain, double nu) {
  mpsfsi::Mat<Dim> f = mpsfsi::Mat<Dim>::Identity() * (1 - nu * strain);
  f(axis, axis) = 1 + strain;
  for (std::size_t i = 0; i < bar.size(); ++i) {
    solver.particles().positions()[i] = f * bar.positions()[i];
    if (bar.positions()[i][axis] < 0.02 || bar.positions()[i][axis] > 0.1) solver.clamp(i);
  }
}

// A lattice of spacing l0 over [0, 0.2]^Dim with every particle moved by up to 0.1 l0 along each
// axis (a fixed Mersenne-Twister sequence): a disordered neighbourhood where A_i is not I/d.
template <int Dim>
mpsfsi::VecArray<Dim> jittered_lattice(double l0, double jitter) {
  auto set = mpsfsi::scenes::lattice_box<Dim>(mpsfsi::Vec<Dim>::Zero(), mpsfsi::Vec<Dim>::Constant(0.2), l0);
  std::mt19937 random(7);
  auto x = set.positions();
  for (auto& p : x)
    for (int k = 0; k < Dim; ++k) p[k] += jitter * l0 * (2.0 * (random() / 4294967296.0) - 1.0);
  return x;
}

}  // namespace

TEST_SUITE("extending") {

TEST_CASE_TEMPLATE("extending: a user's weight function drives FluidSolver and the lattice constants", Dimension,
                   std::integral_constant<int, 2>, std::integral_constant<int, 3>) {
  using namespace mpsfsi;
  constexpr int Dim = Dimension::value;
  const double l0 = kSpacing;
  const auto p = small_dam_break_parameters<Dim>();
  FluidSolver<Dim, QuadraticFluid<Dim>> solver(small_dam_break<Dim>(), p);
  const auto constants = ideal_lattice_constants<Dim, QuadraticWeight>(l0, p.re_density());
  // n0 of the ideal lattice with this weight: the sum over the full neighbourhood.
  double n0 = 0;
  const int c = Dim == 3 ? 3 : 0;
  for (int a = -3; a <= 3; ++a)
    for (int b = -3; b <= 3; ++b)
      for (int e = -c; e <= c; ++e)
        if (a != 0 || b != 0 || e != 0) n0 += QuadraticWeight::value(l0 * std::sqrt(a * a + b * b + e * e), p.re_density());
  CHECK(constants.n0 == doctest::Approx(n0).epsilon(1e-12));
  CHECK(solver.density_constants().n0 == doctest::Approx(n0).epsilon(1e-12));
  for (int k = 0; k < 20; ++k) solver.step();
  CHECK(solver.last_solve().converged);
  double fastest = 0;
  for (std::size_t i = 0; i < solver.particles().size(); ++i)
    fastest = std::max(fastest, solver.particles().velocities()[i].norm());
  CHECK(fastest < 1.0);  // a column 0.1 m high released for 10 ms: free fall reaches 0.1 m/s
}

TEST_CASE_TEMPLATE("extending: a user's gradient correction is exact in a full neighbourhood and runs the fluid",
                   Dimension, std::integral_constant<int, 2>, std::integral_constant<int, 3>) {
  using namespace mpsfsi;
  constexpr int Dim = Dimension::value;
  const double l0 = kSpacing, re = 2.1 * l0, delta = 0.05;
  const auto constants = ideal_lattice_constants<Dim, KoshizukaWeight>(l0, re);
  Vec<Dim> slope;
  for (int k = 0; k < Dim; ++k) slope[k] = k + 1.0;
  // The largest error of the gradient of the linear field slope . x over particles at least
  // re + 0.1 l0 inside the box (full neighbourhoods), relative to |slope|.
  const auto gradient_error = [&](const VecArray<Dim>& x, auto correction) {
    CellListSearch<Dim> search(re);
    search.build(x);
    NeighborList list;
    search.self_query(x, list);
    correction.template update<KoshizukaWeight>(x, list, constants);
    std::vector<double> phi(x.size());
    for (std::size_t i = 0; i < x.size(); ++i) phi[i] = slope.dot(x[i]);
    VecArray<Dim> g;
    gradient<KoshizukaWeight>(x, list, phi, constants, correction, g);
    double worst = 0;
    for (std::size_t i = 0; i < x.size(); ++i)
      if (x[i].minCoeff() > re + 1.1 * l0 && x[i].maxCoeff() < 0.2 - re - 1.1 * l0)
        worst = std::max(worst, (g[i] - slope).norm() / slope.norm());
    return worst;
  };
  // On the regular lattice A_i = I/d, so C_i = d I: the standard operator, exact for a linear field.
  CHECK(gradient_error(jittered_lattice<Dim>(l0, 0.0), RegularisedCorrection<Dim>(delta)) < 1e-12);
  // On the jittered lattice, A_i = I/d + E_i: to first order in E the standard gradient's error
  // is d E slope and this one's d^2 delta / (1 + d delta) E slope, a fraction d delta / (1 + d delta)
  // (0.091 in 2D, 0.130 in 3D), allowed half again for the second-order terms at 10 % jitter;
  // Khayyer & Gotoh's inverse is exact.
  const auto jittered = jittered_lattice<Dim>(l0, 0.1);
  const double standard = gradient_error(jittered, NoGradientCorrection<Dim>());
  const double regularised = gradient_error(jittered, RegularisedCorrection<Dim>(delta));
  const double first_order = Dim * delta / (1 + Dim * delta);
  MESSAGE(Dim << "D jittered lattice, gradient error: standard " << standard << ", regularised " << regularised
              << " (ratio " << regularised / standard << ", first order " << first_order << ")");
  CHECK(gradient_error(jittered, KhayyerGotohCorrection<Dim>()) < 1e-10);
  CHECK(regularised < 1.5 * first_order * standard);

  // The fluid runs with it: 100 steps (50 ms) of the small dam break, surge front and pressure
  // solve against the default correction's.
  const auto p = small_dam_break_parameters<Dim>();
  FluidSolver<Dim> reference(small_dam_break<Dim>(), p);
  FluidSolver<Dim, RegularisedFluid<Dim>> user(small_dam_break<Dim>(), p, RegularisedCorrection<Dim>(delta));
  for (int k = 0; k < 100; ++k) {
    reference.step();
    user.step();
  }
  CHECK(user.last_solve().converged);
  MESSAGE(Dim << "D dam break at 50 ms: surge front " << surge_front(user) << " m, default correction "
              << surge_front(reference) << " m");
  CHECK(std::abs(surge_front(user) - surge_front(reference)) <= l0);  // within one particle spacing
}

TEST_CASE_TEMPLATE("extending: a user's coupling scheme reaches the fixed point the library's Aitken scheme reaches",
                   Dimension, std::integral_constant<int, 2>, std::integral_constant<int, 3>) {
  using namespace mpsfsi;
  constexpr int Dim = Dimension::value;
  constexpr double tolerance = 1e-6;
  const int steps = Dim == 2 ? 5 : 2;
  ConstantRelaxation constant;
  constant.tolerance = tolerance;
  SubIterated aitken;
  aitken.tolerance = tolerance;
  auto user = clamped_structure_in_water<Dim>(constant);
  auto library = clamped_structure_in_water<Dim>(aitken);
  int user_solves = 0, library_solves = 0;
  for (int k = 0; k < steps; ++k) {
    user.step();
    library.step();
    user_solves += user.last_iterations();
    library_solves += library.last_iterations();
  }
  CHECK(user.solid().time() == library.solid().time());
  // Both stop where |F~ - F| <= 1e-6 |F~|: the same load, and so the same displacement, to a few
  // times that, however differently they approach it.
  const auto start = clamped_structure_in_water<Dim>(ExplicitPartitioned{}).solid().particles().positions();
  const auto& x_user = user.solid().particles().positions();
  const auto& x_library = library.solid().particles().positions();
  double largest = 0, apart = 0;
  for (std::size_t s = 0; s < start.size(); ++s) {
    largest = std::max(largest, (x_library[s] - start[s]).norm());
    apart = std::max(apart, (x_user[s] - x_library[s]).norm());
  }
  const double load_apart = (user.total_interface_force() - library.total_interface_force()).norm() /
                            library.total_interface_force().norm();
  MESSAGE(Dim << "D: " << steps << " steps, fluid solves " << user_solves << " (constant relaxation) and "
              << library_solves << " (Aitken); displacements " << apart / largest << " apart (relative), loads "
              << load_apart << " apart");
  REQUIRE(largest > 0);
  CHECK(apart <= 10 * tolerance * largest);
  CHECK(load_apart <= 10 * tolerance);
  CHECK(user_solves > library_solves);  // Aitken's dynamic factor: fewer solves than a fixed 0.5
}

TEST_CASE("extending: the centroid-deviation detector flags a subset of the default's free surface") {
  using namespace mpsfsi;
  auto p = small_dam_break_parameters();
  p.wall_condition = WallCondition::neumann;
  const auto set = small_dam_break();
  FluidSolver<2> plain(set, p);
  FluidSolver<2, UnderIceFluid> under_ice(set, p);
  plain.step();  // the same positions when the surface is detected
  under_ice.step();
  std::size_t plain_flags = 0, under_ice_flags = 0;
  for (std::size_t i = 0; i < set.size(); ++i) {
    CHECK(under_ice.free_surface()[i] <= plain.free_surface()[i]);
    plain_flags += plain.free_surface()[i];
    under_ice_flags += under_ice.free_surface()[i];
  }
  CHECK(under_ice_flags > 0);  // the column's top and open side are still free surface
  MESSAGE("small dam break, first step: " << plain_flags << " flagged by the density test, " << under_ice_flags
                                          << " by the centroid deviation");
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

TEST_CASE_TEMPLATE("extending: a user's failure criterion decides where and along which plane ice cracks", Dimension,
                   std::integral_constant<int, 2>, std::integral_constant<int, 3>) {
  using namespace mpsfsi;
  constexpr int Dim = Dimension::value;
  // A bar stretched along y only (sigma_yy > 0, the lateral stresses about 0): the default
  // criterion breaks it across y, the user's never, since it reads sigma_xx alone.
  const double strain = 2e-3;
  auto params = test::case02_ice<Dim>(kBarSpacing);
  params.tensile_strength = 0.5 * params.youngs_modulus * strain;  // half the stretch's stress
  const auto along_y = stretched_bar<Dim>(1);
  const auto run = [&](auto solver) {
    stretch_and_clamp(solver, along_y, 1, strain, params.poisson_ratio);
    solver.step();
    return solver.failure_log();
  };
  const auto default_log = run(ElasticSolver<Dim, BrittleSolidPolicies<Dim>>(along_y, params));
  REQUIRE(!default_log.empty());
  CHECK(std::abs(default_log.front().normal[1]) > 0.99);  // a crack across y
  CHECK(run(ElasticSolver<Dim, ColumnarIce<Dim>>(along_y, params)).empty());

  // Stretched along x instead, the user's criterion breaks it with the crack plane normal to x.
  const auto along_x = stretched_bar<Dim>(0);
  ElasticSolver<Dim, ColumnarIce<Dim>> s(along_x, params);
  stretch_and_clamp(s, along_x, 0, strain, params.poisson_ratio);
  s.step();
  REQUIRE(!s.failure_log().empty());
  for (const auto& e : s.failure_log()) CHECK(e.normal[0] == 1.0);
}

TEST_CASE_TEMPLATE("extending: a user's failure model with parameters reads strain against its own strength", Dimension,
                   std::integral_constant<int, 2>, std::integral_constant<int, 3>) {
  using namespace mpsfsi;
  constexpr int Dim = Dimension::value;
  // A bar stretched 2e-3 along y under uniaxial stress (plane stress in 2D): the criterion reads
  // that strain (to 1 %: the stress model's Green strain differs from the small strain by
  // strain / 2 = 0.1 %) and the bar breaks when the critical strain is 1.5e-3, not when it is
  // 2.5e-3.
  const double strain = 2e-3;
  const auto bar = stretched_bar<Dim>(1);
  auto params = test::case02_ice<Dim>(kBarSpacing);
  params.tensile_strength = 1e9;  // not read by this model
  const auto run = [&](double critical) {
    ElasticSolver<Dim, StrainLimitedIce<Dim>> solver(
        bar, params, {}, MaxPrincipalStrain{params.youngs_modulus, params.poisson_ratio, critical});
    stretch_and_clamp(solver, bar, 1, strain, params.poisson_ratio);
    CHECK(solver.strengths().front() == critical);
    solver.step();
    Vec<Dim> centre = Vec<Dim>::Constant(0.015);
    centre[1] = 0.065;
    const std::size_t middle = scenes::select(bar, [&](const Vec<Dim>& x) { return (x - centre).norm() < 0.006; })[0];
    CHECK(solver.criterion_stresses()[middle] == doctest::Approx(strain).epsilon(0.01));
    return solver.failure_log().size();
  };
  CHECK(run(1.5e-3) > 0);
  CHECK(run(2.5e-3) == 0);
}

}  // TEST_SUITE
