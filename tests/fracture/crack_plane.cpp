// SPDX-License-Identifier: BSD-3-Clause
#include <doctest/doctest.h>

#include <algorithm>

#include "mpsfsi/fracture/fracture_process.hpp"
#include "mpsfsi/scenes/solid_block.hpp"
#include "mpsfsi/solid/crack_plane.hpp"
#include "mpsfsi/solid/elastic_solver.hpp"
#include "mpsfsi/solid/hwang_model.hpp"
#include "mpsfsi/solid/policy_checks.hpp"
#include "support/ice.hpp"

using namespace mpsfsi;

namespace {

// Brittle policies with no contact, so that a separated piece is truly free in these tests.
template <int Dim>
struct Brittle : BrittleSolidPolicies<Dim> {};

}  // namespace

TEST_SUITE("fracture") {

TEST_CASE_TEMPLATE("fracture.crack_plane: an imposed crack plane cuts a clean straight crack", T,
                   std::integral_constant<int, 2>, std::integral_constant<int, 3>) {
  constexpr int Dim = T::value;
  const double l0 = 0.01;
  Vec<Dim> upper = Vec<Dim>::Constant(0.04);
  upper[0] = 0.1;
  upper[1] = 0.06;
  ElasticSolver<Dim, Brittle<Dim>> s(scenes::material_block<Dim>(Vec<Dim>::Zero(), upper, l0),
                                     test::case02_ice<Dim>(l0));
  // A vertical plane x = 0.055 (through the column of centres at 0.055): every particle of that
  // column fails with normal x, as a crack running across the bar would do.
  std::size_t cut = 0;
  for (std::size_t i = 0; i < s.particles().size(); ++i)
    if (std::abs(s.particles().positions()[i][0] - 0.055) < 1e-9) cut += s.impose_crack(i, Vec<Dim>::UnitX());
  CHECK(cut > 0);
  CHECK(cut == s.cut_bonds());
  const auto& bonds = s.bonds();
  const auto& x = s.particles().positions();
  std::size_t across_intact = 0, cut_elsewhere = 0;
  for (std::size_t i = 0; i < x.size(); ++i)
    for (Offset b = bonds.begin(i); b < bonds.end(i); ++b) {
      const auto j = static_cast<std::size_t>(bonds.neighbor(b));
      const bool crosses = (x[i][0] < 0.05) != (x[j][0] < 0.05);  // the crack lies between x = 0.045 and 0.055
      if (crosses && bonds.intact(b)) ++across_intact;
      if (!crosses && !bonds.intact(b)) ++cut_elsewhere;
    }
  CHECK(across_intact == 0);
  CHECK(cut_elsewhere == 0);
  // The two halves now move independently: pull the right one away, the left stays put.
  for (std::size_t i = 0; i < x.size(); ++i)
    if (x[i][0] > 0.09) s.prescribe_velocity(i, Vec<Dim>::UnitX());
  for (int k = 0; k < 50; ++k) s.step();
  for (std::size_t i = 0; i < x.size(); ++i)
    if (s.reference_positions()[i][0] < 0.04) CHECK(s.particles().velocities()[i].norm() < 1e-12);
}

TEST_CASE_TEMPLATE("fracture.crack_plane: a bar under uniform tension breaks just above sigma_f, not just below", T,
                   std::integral_constant<int, 2>, std::integral_constant<int, 3>) {
  constexpr int Dim = T::value;
  const double l0 = 0.01, strain = 2e-3;
  Vec<Dim> upper = Vec<Dim>::Constant(0.03);
  upper[0] = 0.12;
  const auto bar = scenes::material_block<Dim>(Vec<Dim>::Zero(), upper, l0);
  auto params = test::case02_ice<Dim>(l0);
  params.plane_model = PlaneModel::plane_stress;
  const double nu = params.poisson_ratio;
  // Uniaxial stress state: stretch along x, lateral contraction nu (plane stress / 3D).
  Mat<Dim> f = Mat<Dim>::Identity() * (1 - nu * strain);
  f(0, 0) = 1 + strain;
  Vec<Dim> dir;
  const double sigma1 = MaxPrincipalStress::principal<Dim, double>(detail::cauchy_from_svk<Dim>(f, params.lame()), dir);
  for (const double factor : {0.99, 1.01}) {  // the stress as a fraction of sigma_f
    params.tensile_strength = sigma1 / factor;
    ElasticSolver<Dim, Brittle<Dim>> s(bar, params);
    // Impose the stretched state; hold both ends.
    for (std::size_t i = 0; i < bar.size(); ++i) {
      s.particles().positions()[i] = f * bar.positions()[i];
      if (bar.positions()[i][0] < 0.02 || bar.positions()[i][0] > 0.1) s.clamp(i);
    }
    s.step();
    CAPTURE(factor);
    if (factor < 1) CHECK(s.cut_bonds() == 0);
    else CHECK(s.cut_bonds() > 0);
  }
}

// The solver reads the stresses that the force loop gives with the forces (one pass over the
// bonds for both). What it holds after a step must be the stress model's stresses of the
// committed positions and bonds, to the bit: after steps that cut bonds and steps that cut none.
TEST_CASE_TEMPLATE("fracture.crack_plane: the stresses read with the forces are those of the committed step", T,
                   std::integral_constant<int, 2>, std::integral_constant<int, 3>) {
  constexpr int Dim = T::value;
  static_assert(detail::has_model_forces_with_stresses<CorrectedTotalLagrangian<Dim>, Dim>::value);
  static_assert(!detail::has_model_forces_with_stresses<HwangModel<Dim>, Dim>::value);
  const double l0 = 0.01, strain = 2e-3;
  Vec<Dim> upper = Vec<Dim>::Constant(0.03);
  upper[0] = 0.12;
  const auto bar = scenes::material_block<Dim>(Vec<Dim>::Zero(), upper, l0);
  auto params = test::case02_ice<Dim>(l0);
  params.tensile_strength = 0.5 * params.youngs_modulus * strain;  // below the stretch's stress: it breaks
  ElasticSolver<Dim, Brittle<Dim>> s(bar, params);
  for (std::size_t i = 0; i < bar.size(); ++i) {
    s.particles().positions()[i][0] *= 1 + strain;
    if (bar.positions()[i][0] < 0.02 || bar.positions()[i][0] > 0.1) s.clamp(i);
  }
  std::size_t steps_with_cuts = 0, steps_without = 0;
  for (int k = 0; k < 40; ++k) {
    const std::size_t cut_before = s.cut_bonds();
    s.step();
    (s.cut_bonds() > cut_before ? steps_with_cuts : steps_without) += 1;
    MatArray<Dim> fresh;
    s.stress_model().stresses(s.particles().positions(), s.bonds(), fresh);
    const auto& held = s.stresses();
    REQUIRE(held.size() == fresh.size());
    std::size_t differ = 0;
    for (std::size_t i = 0; i < fresh.size(); ++i) differ += held[i] == fresh[i] ? 0 : 1;
    CAPTURE(k);
    CHECK(differ == 0);
  }
  CHECK(steps_with_cuts > 0);
  CHECK(steps_without > 0);
}

// Pure bending of a block 0.12 m x 0.03 m (x 0.03 m in 3D), imposed exactly (the displacement is
// quadratic, which the second-order fit reproduces): sigma_xx = -E kappa y', largest on the
// bottom face y' = -H/2, where the bottom particles' centres read (H - l0)/H of it (5/6 here).
// The block is clamped outside 0.02 m < x < 0.1 m.
template <int Dim>
struct PureBending {
  static constexpr double l0 = 0.005, height = 0.03, kappa = 0.1;  // curvature 1/m: strain 1.5e-3 at the faces
  ParticleSet<Dim> block;
  SolidParameters<Dim> params = test::case02_ice<Dim>(l0);

  PureBending() {
    Vec<Dim> upper = Vec<Dim>::Constant(height);
    upper[0] = 0.12;
    block = scenes::material_block<Dim>(Vec<Dim>::Zero(), upper, l0);
  }
  Vec<Dim> deformed(const Vec<Dim>& X) const {  // neutral axis y = H/2
    const double nu = params.poisson_ratio;
    const double x = X[0] - 0.06, y = X[1] - height / 2, z = Dim == 3 ? X[Dim - 1] - height / 2 : 0.0;
    Vec<Dim> p = X;
    p[0] += -kappa * x * y;
    p[1] += 0.5 * kappa * (x * x + nu * (y * y - z * z));
    if constexpr (Dim == 3) p[2] += kappa * nu * y * z;
    return p;
  }
  double stress_at(double y_from_axis) const {  // sigma_1 on the mid-span section
    const double nu = params.poisson_ratio;
    Mat<Dim> f = Mat<Dim>::Identity();
    f(0, 0) += -kappa * y_from_axis;
    f(1, 1) += kappa * nu * y_from_axis;
    if constexpr (Dim == 3) f(2, 2) += kappa * nu * y_from_axis;
    Vec<Dim> dir;
    return MaxPrincipalStress::principal<Dim, double>(detail::cauchy_from_svk<Dim>(f, params.lame()), dir);
  }
  double surface_stress() const { return stress_at(-height / 2); }
  double centre_stress() const { return stress_at(-height / 2 + l0 / 2); }
  template <class Solver>
  void impose(Solver& s) const {
    for (std::size_t i = 0; i < block.size(); ++i) {
      s.particles().positions()[i] = deformed(block.positions()[i]);
      if (block.positions()[i][0] < 0.02 || block.positions()[i][0] > 0.1) s.clamp(i);
    }
  }
};

// The criterion reads the stress on the body's surface, not at the outer particles' centres l0/2
// inside it (SolidParameters::failure_stress_at_surface). Set sigma_f just below / above the
// surface value of pure bending.
TEST_CASE_TEMPLATE("fracture.crack_plane: under pure bending the criterion reads the stress at the surface", T,
                   std::integral_constant<int, 2>, std::integral_constant<int, 3>) {
  constexpr int Dim = T::value;
  PureBending<Dim> bending;
  const double surface = bending.surface_stress();
  REQUIRE(bending.centre_stress() < 0.9 * surface);
  for (const bool at_surface : {true, false})
    for (const double factor : {0.99, 1.01}) {  // the surface stress as a fraction of sigma_f
      auto params = bending.params;
      params.tensile_strength = surface / factor;
      params.failure_stress_at_surface = at_surface;
      ElasticSolver<Dim, Brittle<Dim>> s(bending.block, params);
      bending.impose(s);
      s.step();
      CAPTURE(at_surface);
      CAPTURE(factor);
      if (at_surface && factor > 1) {
        REQUIRE(s.cut_bonds() > 0);
        // The first failure is on the bottom face, with a vertical crack plane.
        const auto& first = s.failure_log().front();
        CHECK(s.reference_positions()[first.particle][1] < bending.l0);
        CHECK(std::abs(first.normal[0]) > 0.99);
      } else {
        CHECK(s.cut_bonds() == 0);
      }
    }
}

// A face that has carried an external force is not read at the surface afterwards: the load's
// spikes stay in the field after it is gone (failure_stress.hpp). The bottom face carries a
// negligible force for one step and none after; with sigma_f between the centre and the surface
// stress it must not fail, while the same face never loaded fails at the first step.
TEST_CASE("fracture.crack_plane: a face that has carried a load is read at particle centres from then on") {
  PureBending<2> bending;
  auto params = bending.params;
  params.tensile_strength = bending.surface_stress() / 1.01;
  REQUIRE(bending.centre_stress() < 0.9 * params.tensile_strength);
  for (const bool loaded_once : {false, true}) {
    ElasticSolver<2, Brittle<2>> s(bending.block, params);
    bending.impose(s);
    if (loaded_once)
      for (std::size_t i = 0; i < bending.block.size(); ++i)
        if (bending.block.positions()[i][1] < bending.l0) s.external_force()[i] = Vec<2>(0, 1e-9);
    s.step();
    std::fill(s.external_force().begin(), s.external_force().end(), Vec<2>::Zero());
    s.step();
    CAPTURE(loaded_once);
    CHECK((s.cut_bonds() > 0) == !loaded_once);
  }
}

}
