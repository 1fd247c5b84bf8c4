// SPDX-License-Identifier: BSD-3-Clause
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <vector>

#include "mpsfsi/core/error.hpp"
#include "mpsfsi/fracture/fracture_process.hpp"
#include "mpsfsi/fracture/strength.hpp"
#include "mpsfsi/scenes/solid_block.hpp"
#include "mpsfsi/solid/elastic_solver.hpp"
#include "support/ice.hpp"

using namespace mpsfsi;

namespace {

StrengthSetup setup_for(const std::vector<Index>& ids, double l0 = 0.002) {
  StrengthSetup s;
  s.tensile_strength = 1e6;
  s.youngs_modulus = 5e9;
  s.poisson_ratio = 0.3;
  s.l0 = l0;
  s.particle_volume = l0 * l0;
  s.ids = &ids;
  return s;
}

template <class Failure>
struct WithFailure : SolidDefaults<2> {
  using failure = Failure;
};

// Assigns one strength that is not positive (a model written wrong).
struct ZeroStrength : MaxPrincipalStress {
  void assign_strengths(const StrengthSetup& s, std::vector<double>& strength) const {
    strength.assign(s.ids->size(), 1e6);
    strength.back() = 0;
  }
};

}  // namespace

TEST_SUITE("fracture") {

// Kolmogorov-Smirnov against the per-particle law P(sigma_i <= s) = 1 - exp(-(V_p/V0)(s/sigma_0)^m):
// with 20,000 draws the 1 % critical distance is 1.63 / sqrt(20000) = 0.0115.
TEST_CASE("fracture.strength: Weibull strengths follow the per-particle law, keyed to particle ids") {
  std::vector<Index> ids(20000);
  std::iota(ids.begin(), ids.end(), 0);
  const WeibullStrength<> model(6.0, 1e-4, 7);
  std::vector<double> strength;
  model.assign_strengths(setup_for(ids), strength);
  REQUIRE(strength.size() == ids.size());
  std::vector<double> sorted = strength;
  std::sort(sorted.begin(), sorted.end());
  const double ratio = 0.002 * 0.002 / 1e-4;
  double d = 0;
  for (std::size_t k = 0; k < sorted.size(); ++k) {
    const double cdf = 1 - std::exp(-ratio * std::pow(sorted[k] / 1e6, 6.0));
    d = std::max({d, std::abs(cdf - double(k) / sorted.size()), std::abs(cdf - double(k + 1) / sorted.size())});
  }
  CHECK(d < 1.63 / std::sqrt(double(sorted.size())));

  SUBCASE("a particle keeps its strength when the particles are reordered") {
    std::vector<Index> reversed(ids.rbegin(), ids.rend());
    std::vector<double> again;
    model.assign_strengths(setup_for(reversed), again);
    for (std::size_t k = 0; k < ids.size(); k += 997) CHECK(again[ids.size() - 1 - k] == strength[k]);
  }
  SUBCASE("another seed draws another sample") {
    std::vector<double> other;
    WeibullStrength<>(6.0, 1e-4, 8).assign_strengths(setup_for(ids), other);
    std::size_t same = 0;
    for (std::size_t k = 0; k < ids.size(); ++k) same += other[k] == strength[k];
    CHECK(same == 0);
  }
  SUBCASE("missing parameters are named") {
    CHECK_THROWS_WITH_AS(WeibullStrength<>(0.0, 1e-4).assign_strengths(setup_for(ids), strength),
                         doctest::Contains("Weibull modulus"), InvalidInput);
    CHECK_THROWS_WITH_AS(WeibullStrength<>(6.0, 0.0).assign_strengths(setup_for(ids), strength),
                         doctest::Contains("reference volume"), InvalidInput);
  }
}

// sigma_c = sqrt(2 E G_c / l0) where that is below sigma_f (l0 above h_max = 2 E G_c / sigma_f^2),
// sigma_f otherwise.
TEST_CASE("fracture.strength: the crack band strength scales as 1/sqrt(l0) above h_max") {
  std::vector<Index> ids(10);
  std::iota(ids.begin(), ids.end(), 0);
  CrackBandStrength<> model(1.0);  // ice-like G_c: h_max = 2 * 5e9 * 1 / (1e6)^2 = 10 mm
  model.quiet = true;
  std::vector<double> strength;
  model.assign_strengths(setup_for(ids, 0.02), strength);
  CHECK(strength.front() == doctest::Approx(std::sqrt(2 * 5e9 * 1.0 / 0.02)));  // 707 kPa
  CHECK(std::all_of(strength.begin(), strength.end(), [&](double s) { return s == strength.front(); }));
  model.assign_strengths(setup_for(ids, 0.08), strength);
  CHECK(strength.front() == doctest::Approx(std::sqrt(2 * 5e9 * 1.0 / 0.08)));  // half as strong
  model.assign_strengths(setup_for(ids, 0.005), strength);
  CHECK(strength.front() == 1e6);  // below h_max: sigma_f
  CHECK_THROWS_WITH_AS(CrackBandStrength<>(0.0).assign_strengths(setup_for(ids), strength),
                       doctest::Contains("fracture energy"), InvalidInput);
}

TEST_CASE("fracture.strength: ElasticSolver gives every particle its model's strength") {
  const double l0 = 0.01;
  const auto block = scenes::material_block<2>(Vec<2>::Zero(), Vec<2>(0.1, 0.04), l0);
  auto params = test::case02_ice<2>(l0);
  params.tensile_strength = 1e6;
  SUBCASE("a criterion without strengths of its own: sigma_f everywhere") {
    ElasticSolver<2, BrittleSolidPolicies<2>> solver(block, params);
    REQUIRE(solver.strengths().size() == block.size());
    CHECK(std::all_of(solver.strengths().begin(), solver.strengths().end(), [](double s) { return s == 1e6; }));
  }
  SUBCASE("a Weibull model: its draws, also in the output field") {
    using Model = WeibullStrength<>;
    ElasticSolver<2, WithFailure<Model>> solver(block, params, {}, Model(8.0, 1e-4, 3));
    std::vector<double> expected;
    Model(8.0, 1e-4, 3).assign_strengths(setup_for(solver.particles().ids(), l0), expected);
    CHECK(solver.strengths() == expected);
    CHECK(solver.failure_model().seed == 3);
  }
  SUBCASE("without a failure model there is no strength") {
    ElasticSolver<2> solver(block, params);
    CHECK(solver.strengths().empty());
    CHECK(solver.criterion_stresses().empty());
  }
  SUBCASE("a strength that is not positive is an error") {
    CHECK_THROWS_WITH_AS((ElasticSolver<2, WithFailure<ZeroStrength>>(block, params)),
                         doctest::Contains("strength that is not positive"), InvalidInput);
  }
}

}  // TEST_SUITE
