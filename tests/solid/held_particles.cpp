// SPDX-License-Identifier: BSD-3-Clause
#include <doctest/doctest.h>

#include <cmath>
#include <random>

#include "mpsfsi/core/parallel.hpp"
#include "mpsfsi/kernels/lattice_constants.hpp"
#include "mpsfsi/kernels/weight.hpp"
#include "mpsfsi/scenes/solid_block.hpp"
#include "mpsfsi/solid/corrected_total_lagrangian.hpp"
#include "mpsfsi/solid/detail/held_particles.hpp"
#include "mpsfsi/solid/elastic_solver.hpp"

using namespace mpsfsi;

namespace {

const LameConstants<double> kLame{1.5e6, 1.0e6};

// A block of 24 x 5 (x 3) cells whose first 12 columns are prescribed with one velocity and sit
// at their reference sites shifted by a common translation; the rest is deformed at random. With
// re = 2.1 l0 a bond spans at most two columns, so a clamped particle is quiet when its column is
// at least two from the free part (columns 0-9), and held when at least four (columns 0-7): in
// rows of 24, whole groups of the force loop for 2, 4 and 8 lanes.
template <int Dim>
struct ClampedBlock {
  static constexpr int columns = 24, clamped_columns = 12, last_held_column = 7;
  double l0 = 0.01;
  ParticleSet<Dim> set;
  BondList<Dim> bonds;
  ParticleConstraints<Dim> constraints;
  VecArray<Dim> x;
  ClampedBlock() {
    Vec<Dim> upper = Vec<Dim>::Constant(3 * l0);
    upper[0] = columns * l0;
    upper[1] = 5 * l0;
    set = scenes::material_block<Dim>(Vec<Dim>::Zero(), upper, l0);
    bonds.template build<KoshizukaWeight>(set.positions(), std::vector<std::int32_t>(set.size(), 0), 2.1 * l0);
    constraints.reset(set.size());
    x = set.positions();
    std::mt19937 rng(3);
    std::uniform_real_distribution<double> u(-0.05 * l0, 0.05 * l0);
    const Vec<Dim> shift = Vec<Dim>::Constant(0.2);
    for (std::size_t i = 0; i < x.size(); ++i) {
      if (column(i) < clamped_columns) {
        constraints.prescribe(i, Vec<Dim>::Constant(-0.3));
        x[i] += shift;
      } else {
        for (int a = 0; a < Dim; ++a) x[i][a] += u(rng) + 0.02 * x[i][0];
        x[i] += shift;
      }
    }
  }
  int column(std::size_t i) const { return static_cast<int>(std::floor(set.positions()[i][0] / l0)); }
};

template <int Dim>
struct EvaluatingModel : CorrectedTotalLagrangian<Dim> {
  void skip_held(const std::vector<std::uint8_t>*) = delete;
};
template <int Dim>
struct EvaluatingPolicies : SolidDefaults<Dim> {
  using stress_model = EvaluatingModel<Dim>;
};

// A beam on two clamped supports, pressed in the middle by an indenter that moves down: three
// bodies besides the beam, each all prescribed, so the solver's force loop skips them.
template <int Dim, class Policies>
ElasticSolver<Dim, Policies> pressed_beam(double l0, std::vector<std::size_t>& indenter) {
  Vec<Dim> upper = Vec<Dim>::Constant(3 * l0);
  upper[0] = 20 * l0;
  upper[1] = 4 * l0;
  ParticleSet<Dim> set = scenes::material_block<Dim>(Vec<Dim>::Zero(), upper, l0);
  std::vector<std::int32_t> body(set.size(), 0);
  auto add_block = [&](double x0, double y0, int id) {
    for (int k = 0; k < (Dim == 3 ? 3 : 1); ++k)
      for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 5; ++c) {
          Vec<Dim> p = Vec<Dim>::Zero();
          p[0] = x0 + (c + 0.5) * l0;
          p[1] = y0 + (r + 0.5) * l0;
          if constexpr (Dim == 3) p[2] = (k + 0.5) * l0;
          const auto i = static_cast<std::size_t>(set.add(p, ParticleKind::solid));
          body.push_back(id);
          if (id == 3) indenter.push_back(i);
        }
  };
  // One contact distance (l0) from the beam's outer rows.
  add_block(0, -3 * l0, 1);
  add_block(15 * l0, -3 * l0, 2);
  add_block(7.5 * l0, 4 * l0, 3);
  SolidParameters<Dim> p;
  p.l0 = l0;
  p.density = 1000;
  p.youngs_modulus = 1e7;
  p.poisson_ratio = 0.3;
  ElasticSolver<Dim, Policies> s(set, p, body);
  for (std::size_t i = 0; i < set.size(); ++i)
    if (body[i] == 1 || body[i] == 2) s.clamp(i);
  for (const std::size_t i : indenter) s.prescribe_velocity(i, -0.5 * Vec<Dim>::UnitY());
  return s;
}

}  // namespace

TEST_SUITE("solid") {

TEST_CASE_TEMPLATE("solid.held_particles: held are the prescribed particles two bonds deep in an unstrained, "
                   "uniformly moving neighbourhood",
                   T, std::integral_constant<int, 2>, std::integral_constant<int, 3>) {
  constexpr int Dim = T::value;
  ClampedBlock<Dim> block;
  detail::HeldParticles<Dim> held;
  const auto* marks = held.mark(block.constraints, block.bonds, block.x);
  REQUIRE(marks != nullptr);
  REQUIRE(marks->size() == block.x.size());
  std::size_t count = 0;
  for (std::size_t i = 0; i < block.x.size(); ++i) {
    CAPTURE(i);
    CHECK(((*marks)[i] != 0) == (block.column(i) <= block.last_held_column));
    count += (*marks)[i];
  }
  CHECK(count > 0);

  SUBCASE("a strain of 1e-6 in one bond takes its particle's neighbourhood out") {
    const std::size_t i = 0;  // a corner of the held region
    block.x[i][1] += 1e-6 * block.l0;
    marks = held.mark(block.constraints, block.bonds, block.x);
    REQUIRE(marks != nullptr);
    for (Offset b = block.bonds.begin(i); b < block.bonds.end(i); ++b)
      CHECK((*marks)[static_cast<std::size_t>(block.bonds.neighbor(b))] == 0);
    CHECK((*marks)[i] == 0);
  }
  SUBCASE("a round-off displacement (1e-12 l0) changes nothing") {
    block.x[0][1] += 1e-12 * block.l0;
    const auto* again = held.mark(block.constraints, block.bonds, block.x);
    REQUIRE(again != nullptr);
    for (std::size_t i = 0; i < block.x.size(); ++i) CHECK(((*again)[i] != 0) == (block.column(i) <= block.last_held_column));
  }
  SUBCASE("a different velocity takes the particle's neighbourhood out") {
    const std::size_t i = 0;
    block.constraints.prescribe(i, Vec<Dim>::Constant(-0.3 + 1e-9));
    marks = held.mark(block.constraints, block.bonds, block.x);
    REQUIRE(marks != nullptr);
    CHECK((*marks)[i] == 0);
    for (Offset b = block.bonds.begin(i); b < block.bonds.end(i); ++b)
      CHECK((*marks)[static_cast<std::size_t>(block.bonds.neighbor(b))] == 0);
  }
  SUBCASE("no prescribed particle, or support constraints only: none held") {
    for (std::size_t i = 0; i < block.x.size(); ++i)
      if (i % 2) block.constraints.support(i, Vec<Dim>::UnitY());
      else block.constraints.release(i);
    CHECK(held.mark(block.constraints, block.bonds, block.x) == nullptr);
  }
}

// The force loop that skips the held particles gives the forces, stresses and kept fits of the
// loop that evaluates them, to round-off (the held ones' are zero and [I 0] to round-off there),
// on 1 to 3 threads, with the bond viscosity at random velocities of the free particles.
TEST_CASE_TEMPLATE("solid.held_particles: skipping the held particles changes no force, stress or fit", T,
                   std::integral_constant<int, 2>, std::integral_constant<int, 3>) {
  constexpr int Dim = T::value;
  ClampedBlock<Dim> block;
  CorrectedTotalLagrangian<Dim> model;
  const auto c = ideal_lattice_constants<Dim, KoshizukaWeight>(block.l0, 2.1 * block.l0);
  model.initialize(block.bonds, SolidModelContext<Dim>{kLame, 1000.0, block.l0, std::pow(block.l0, Dim), c.n0, c.lambda});
  const std::size_t n = block.x.size();
  VecArray<Dim> v(n);
  std::mt19937 rng(9);
  std::uniform_real_distribution<double> speed(-0.1, 0.1);
  for (std::size_t i = 0; i < n; ++i)
    for (int a = 0; a < Dim; ++a) v[i][a] = block.constraints.at(i) == Constraint::prescribed ? -0.3 : speed(rng);
  detail::HeldParticles<Dim> held;
  const auto* marks = held.mark(block.constraints, block.bonds, block.x);
  REQUIRE(marks != nullptr);
  const std::vector<std::uint8_t> all(n, 1);
  const double zeta = 50.0;
  const int saved = parallel::max_threads();
  for (int threads = 1; threads <= 3; ++threads) {
    CAPTURE(threads);
    parallel::set_num_threads(threads);
    VecArray<Dim> full, skipped;
    MatArray<Dim> full_stress, skipped_stress;
    model.keep_affine(&all);
    model.internal_forces(block.x, v, block.bonds, full, &full_stress, zeta);
    const auto full_fits = model.kept_affine();
    model.keep_affine(&all);
    model.skip_held(marks);
    REQUIRE(model.skips_held(n));
    model.internal_forces(block.x, v, block.bonds, skipped, &skipped_stress, zeta);
    CHECK(!model.skips_held(n));  // for one loop only
    const auto& skipped_fits = model.kept_affine();
    double scale = 0, stress_scale = 0, worst = 0, worst_stress = 0, worst_fit = 0;
    for (std::size_t i = 0; i < n; ++i) {
      scale = std::max(scale, full[i].norm());
      stress_scale = std::max(stress_scale, full_stress[i].norm());
      worst = std::max(worst, (skipped[i] - full[i]).norm());
      worst_stress = std::max(worst_stress, (skipped_stress[i] - full_stress[i]).norm());
      worst_fit = std::max(worst_fit, (skipped_fits[i] - full_fits[i]).norm());
    }
    REQUIRE(scale > 0);
    REQUIRE(stress_scale > 0);
    CHECK(worst < 1e-12 * scale);
    CHECK(worst_stress < 1e-12 * stress_scale);
    CHECK(worst_fit < 1e-12);
    for (std::size_t i = 0; i < n; ++i)
      if ((*marks)[i]) CHECK(skipped_stress[i] == Mat<Dim>::Zero());  // skipped, not evaluated
  }
  parallel::set_num_threads(saved);
}


TEST_CASE_TEMPLATE("solid.held_particles: ElasticSolver gives the same motion and loads with the held bodies skipped",
                   T, std::integral_constant<int, 2>, std::integral_constant<int, 3>) {
  constexpr int Dim = T::value;
  static_assert(detail::skips_held<CorrectedTotalLagrangian<Dim>>::value);
  static_assert(!detail::skips_held<EvaluatingModel<Dim>>::value);
  const double l0 = 0.01;
  std::vector<std::size_t> indenter, unused;
  auto skipping = pressed_beam<Dim, SolidDefaults<Dim>>(l0, indenter);
  auto evaluating = pressed_beam<Dim, EvaluatingPolicies<Dim>>(l0, unused);
  double worst = 0, travel = 0, load = 0, load_difference = 0;
  for (int k = 0; k < 400; ++k) {
    skipping.step();
    evaluating.step();
  }
  const auto& a = skipping.particles().positions();
  const auto& b = evaluating.particles().positions();
  const auto& x0 = skipping.reference_positions();
  for (std::size_t i = 0; i < a.size(); ++i) {
    worst = std::max(worst, (a[i] - b[i]).norm());
    travel = std::max(travel, (b[i] - x0[i]).norm());
  }
  for (const std::size_t i : indenter) {
    load += evaluating.reaction(i)[1];
    load_difference += skipping.reaction(i)[1] - evaluating.reaction(i)[1];
  }
  CHECK(skipping.contact().active_pairs() > 0);  // the indenter presses on the beam
  REQUIRE(travel > 0);
  REQUIRE(std::abs(load) > 0);
  CHECK(worst < 1e-9 * travel);
  CHECK(std::abs(load_difference) < 1e-9 * std::abs(load));
}

}
