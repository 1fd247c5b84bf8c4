// SPDX-License-Identifier: BSD-3-Clause
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <utility>
#include <vector>

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

// A face that carries an external force is read at the particle centres (failure_stress.hpp:
// point loads leave spikes that a fit extrapolated to the surface would read), unless the force
// is declared a distributed traction (ElasticSolver::mark_distributed_load): then it is read on the
// surface as a free face is. sigma_f 1 % below the surface stress of pure bending, above the
// centres' 5/6 of it; a small upward force on every particle of the bottom (tensile) face, which
// moves nothing measurably in one step.
TEST_CASE_TEMPLATE(
    "fracture.crack_plane: a face under a distributed load is read at the surface, under loads at the centres", T,
    std::integral_constant<int, 2>, std::integral_constant<int, 3>) {
  constexpr int Dim = T::value;
  PureBending<Dim> bending;
  auto params = bending.params;
  params.tensile_strength = bending.surface_stress() / 1.01;
  for (const bool distributed : {false, true}) {
    ElasticSolver<Dim, Brittle<Dim>> s(bending.block, params);
    bending.impose(s);
    for (std::size_t i = 0; i < bending.block.size(); ++i)
      if (bending.block.positions()[i][1] < bending.l0) {
        s.external_force()[i] = 1e-3 * Vec<Dim>::UnitY();
        if (distributed) s.mark_distributed_load(i);
      }
    s.step();
    CAPTURE(distributed);
    if (distributed) {
      REQUIRE(s.cut_bonds() > 0);
      CHECK(s.reference_positions()[s.failure_log().front().particle][1] < bending.l0);
    } else {
      CHECK(s.cut_bonds() == 0);
    }
  }
  ElasticSolver<Dim, Brittle<Dim>> s(bending.block, params);
  CHECK_THROWS_WITH_AS(s.mark_distributed_load(bending.block.size()),
                       doctest::Contains("mark_distributed_load: particle"), InvalidInput);
}

// MaxPrincipalStress's upper bound lets the check skip sigma_1 where a particle cannot fail, and
// the `failure_stress` field gets it later (FractureProcess::refresh_output). Against the same
// criterion without the bound, on pure bending with sigma_f between the centre and the surface
// stress (so the bottom face fails and the interior is screened out), both with the stress read at
// the surface and averaged and read at the centres: the same cuts, the same failures, and the
// same field to the bit, read through output() and through criterion_stresses().
struct UnscreenedMaxPrincipal {
  static constexpr bool enabled = true;
  template <int Dim, class Scalar>
  static Scalar principal(const Mat<Dim, Scalar>& sigma, Vec<Dim, Scalar>& direction) {
    return MaxPrincipalStress::principal<Dim, Scalar>(sigma, direction);
  }
};
template <int Dim>
struct BrittleUnscreened : BrittleSolidPolicies<Dim> {
  using failure = UnscreenedMaxPrincipal;
};

TEST_CASE_TEMPLATE("fracture.crack_plane: screening by the upper bound changes no check and no output", T,
                   std::integral_constant<int, 2>, std::integral_constant<int, 3>) {
  constexpr int Dim = T::value;
  static_assert(detail::has_failure_upper_bound<MaxPrincipalStress, Dim>::value);
  static_assert(!detail::has_failure_upper_bound<UnscreenedMaxPrincipal, Dim>::value);
  PureBending<Dim> bending;
  for (const bool averaged : {true, false}) {
    auto params = bending.params;
    params.tensile_strength = 0.5 * (bending.surface_stress() + bending.centre_stress());
    params.average_failure_stress = averaged;
    ElasticSolver<Dim, Brittle<Dim>> screened(bending.block, params);
    ElasticSolver<Dim, BrittleUnscreened<Dim>> plain(bending.block, params);
    bending.impose(screened);
    bending.impose(plain);
    std::size_t below_strength = 0;
    for (int k = 0; k < 20; ++k) {
      screened.step();
      plain.step();
      CAPTURE(averaged);
      CAPTURE(k);
      REQUIRE(screened.cut_bonds() == plain.cut_bonds());
      REQUIRE(screened.failure_events() == plain.failure_events());
      // Odd steps through output() (the field as written to files), even ones through the accessor.
      std::vector<double> a;
      if (k % 2)
        screened.output().for_each_scalar_field([&](const std::string& name, const std::vector<double>& field) {
          if (name == "failure_stress") a = field;
        });
      else
        a = screened.criterion_stresses();
      const auto& b = plain.criterion_stresses();
      REQUIRE(a.size() == b.size());
      std::size_t differ = 0;
      for (std::size_t i = 0; i < a.size(); ++i) {
        differ += a[i] == b[i] ? 0 : 1;
        below_strength += b[i] != 0 && b[i] < 0.5 * params.tensile_strength ? 1 : 0;
      }
      CHECK(differ == 0);
    }
    CHECK(screened.cut_bonds() > 0);
    CHECK(below_strength > 0);  // particles the bound screens out
  }
}

// The default stress model with its keeping of the surface fits removed: the read-out then fits
// every surface particle itself (DeformationFit::affine).
template <int Dim>
struct RefittingModel : CorrectedTotalLagrangian<Dim> {
  void keep_affine(const std::vector<std::uint8_t>*) = delete;
};
template <int Dim>
struct BrittleRefitting : BrittleSolidPolicies<Dim> {
  using stress_model = RefittingModel<Dim>;
};

TEST_CASE_TEMPLATE("fracture.crack_plane: the surface read from the force loop's fits is the read from fits of its own", T,
                   std::integral_constant<int, 2>, std::integral_constant<int, 3>) {
  constexpr int Dim = T::value;
  static_assert(detail::keeps_affine<CorrectedTotalLagrangian<Dim>>::value);
  static_assert(!detail::keeps_affine<RefittingModel<Dim>>::value);
  PureBending<Dim> bending;
  auto params = bending.params;
  params.tensile_strength = 0.5 * (bending.surface_stress() + bending.centre_stress());
  ElasticSolver<Dim, Brittle<Dim>> kept(bending.block, params);
  ElasticSolver<Dim, BrittleRefitting<Dim>> refitted(bending.block, params);
  bending.impose(kept);
  bending.impose(refitted);
  // Steps with cuts (the fits of the particles that lost bonds change, and the forces are
  // computed again) and without.
  for (int k = 0; k < 20; ++k) {
    CAPTURE(k);
    kept.step();
    refitted.step();
    REQUIRE(kept.cut_bonds() == refitted.cut_bonds());
    REQUIRE(kept.failure_events() == refitted.failure_events());
    const auto& a = kept.criterion_stresses();
    const auto& b = refitted.criterion_stresses();
    REQUIRE(a.size() == b.size());
    double worst = 0, scale = 0;
    for (std::size_t i = 0; i < a.size(); ++i) {
      worst = std::max(worst, std::abs(a[i] - b[i]));
      scale = std::max(scale, std::abs(b[i]));
    }
    CHECK(scale > 0);
    CHECK(worst <= 1e-12 * scale);  // round-off: the same fit summed in another order
  }
  CHECK(kept.cut_bonds() > 0);
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

// CrackSide::attachment: a principal direction has no sign; the failing particle stays with the
// side that holds it more firmly, whatever sign the direction came with, and a mirror image of the
// neighbourhood, deformed or not, gives the mirror image of the normal (docs/theory.md, 5.3).
TEST_CASE_TEMPLATE("fracture.crack_plane: a failing particle stays with the side it is held to, mirror images alike", T,
                   std::integral_constant<int, 2>, std::integral_constant<int, 3>) {
  constexpr int Dim = T::value;
  const double l0 = 0.01, re = 2.1 * l0, mid = 0.035;
  const auto block = scenes::material_block<Dim>(Vec<Dim>::Zero(), Vec<Dim>::Constant(0.07), l0);  // 7 columns
  const auto& x = block.positions();
  // The image of a particle in the plane x = mid; the centre particle is its own image.
  const auto mirror = [&](Vec<Dim> p) {
    p[0] = 2 * mid - p[0];
    return p;
  };
  std::vector<std::size_t> image(x.size(), x.size());
  for (std::size_t i = 0; i < x.size(); ++i)
    for (std::size_t j = 0; j < x.size(); ++j)
      if ((x[j] - mirror(x[i])).norm() < 1e-9) image[i] = j;
  std::size_t c = x.size();
  for (std::size_t i = 0; i < x.size(); ++i)
    if ((x[i] - Vec<Dim>::Constant(mid)).norm() < 1e-9) c = i;
  REQUIRE(c < x.size());
  REQUIRE(image[c] == c);
  const auto fresh_bonds = [&] {
    BondList<Dim> bonds;
    bonds.template build<KoshizukaWeight>(x, std::vector<std::int32_t>(x.size(), 0), re);
    return bonds;
  };
  Vec<Dim> tilted = Vec<Dim>::Zero();
  tilted[0] = 0.96;
  tilted[1] = 0.28;
  const auto mirrored_normal = [](Vec<Dim> n) {
    n[0] = -n[0];
    return n;
  };
  // An undamaged lattice at rest is a tie: the normal keeps the sign it came with.
  const BondList<Dim> intact = fresh_bonds();
  CHECK(orient_toward_attachment(intact, x, c, tilted) == tilted);
  CHECK(orient_toward_attachment(intact, x, c, Vec<Dim>(-tilted)) == Vec<Dim>(-tilted));
  // c's bonds to the columns on its right cut: it is held from the left, so the normal points
  // left whatever its sign was; the mirror image (bonds to the left cut) gives the image normal.
  for (const double side : {1.0, -1.0}) {
    BondList<Dim> bonds = fresh_bonds();
    for (Offset b = bonds.begin(c); b < bonds.end(c); ++b)
      if (side * (x[static_cast<std::size_t>(bonds.neighbor(b))][0] - mid) > 0.5 * l0) bonds.cut(b);
    for (const double sign : {1.0, -1.0}) {
      const Vec<Dim> n = orient_toward_attachment(bonds, x, c, Vec<Dim>(sign * tilted));
      CAPTURE(side);
      CAPTURE(sign);
      CHECK(n[0] == doctest::Approx(-0.96 * side));
      CHECK(n[1] == doctest::Approx(-0.28 * side));
    }
  }
  // A random deformation and its mirror image: the normals are mirror images.
  std::srand(7);
  const auto random = [] { return 2.0 * std::rand() / RAND_MAX - 1.0; };
  for (int trial = 0; trial < 20; ++trial) {
    VecArray<Dim> moved(x.size()), moved_image(x.size());
    for (std::size_t i = 0; i < x.size(); ++i)
      for (int k = 0; k < Dim; ++k) moved[i][k] = x[i][k] + 0.05 * l0 * random();
    for (std::size_t i = 0; i < x.size(); ++i) moved_image[image[i]] = mirror(moved[i]);
    Vec<Dim> n;
    for (int k = 0; k < Dim; ++k) n[k] = random();
    n.normalize();
    const Vec<Dim> chosen = orient_toward_attachment(intact, moved, c, n);
    const Vec<Dim> chosen_image = orient_toward_attachment(intact, moved_image, c, mirrored_normal(n));
    CAPTURE(trial);
    CHECK((chosen_image - mirrored_normal(chosen)).norm() < 1e-12);
  }
}

// CrackSide::slab: the failing particle's slab |(x - x_c) . n| < l0/2 loses its bonds across both
// faces. On a lattice at rest with n along a lattice axis that is exactly what the one-sided rule
// cuts with +n and with -n together; the cut does not depend on the sign of n, keeps the bonds
// inside the slab, and a mirror image of the lattice in the plane gives the mirror-image cut.
TEST_CASE_TEMPLATE("fracture.crack_plane: a slab failure cuts both faces of the failing particle's slab", T,
                   std::integral_constant<int, 2>, std::integral_constant<int, 3>) {
  constexpr int Dim = T::value;
  const double l0 = 0.01, re = 2.1 * l0, mid = 0.035, half_width = std::sqrt(double(Dim)) / 2 * l0;
  const auto block = scenes::material_block<Dim>(Vec<Dim>::Zero(), Vec<Dim>::Constant(0.07), l0);
  const auto& x = block.positions();
  std::size_t c = x.size();
  for (std::size_t i = 0; i < x.size(); ++i)
    if ((x[i] - Vec<Dim>::Constant(mid)).norm() < 1e-9) c = i;
  REQUIRE(c < x.size());
  const auto fresh_bonds = [&] {
    BondList<Dim> bonds;
    bonds.template build<KoshizukaWeight>(x, std::vector<std::int32_t>(x.size(), 0), re);
    return bonds;
  };
  std::vector<std::size_t> touched, scratch;
  const auto cut_set = [&](const Vec<Dim>& n, double slab) {
    BondList<Dim> bonds = fresh_bonds();
    cut_bonds_across_plane(bonds, x, c, n, half_width, re, touched, scratch, slab);
    std::vector<char> cut(bonds.num_bonds());
    for (std::size_t b = 0; b < cut.size(); ++b) cut[b] = !bonds.intact(static_cast<Offset>(b));
    return std::make_pair(cut, bonds);
  };
  const Vec<Dim> n = Vec<Dim>::UnitX();
  const auto [slab, bonds] = cut_set(n, 0.5 * l0);
  CHECK(slab == cut_set(Vec<Dim>(-n), 0.5 * l0).first);
  const auto plus = cut_set(n, 0.0).first, minus = cut_set(Vec<Dim>(-n), 0.0).first;
  std::size_t cut_count = 0;
  for (std::size_t b = 0; b < slab.size(); ++b) {
    CHECK(slab[b] == (plus[b] || minus[b]));
    cut_count += slab[b];
  }
  CHECK(cut_count > 0);
  // c keeps exactly its bonds inside its slab (its own column).
  for (Offset b = bonds.begin(c); b < bonds.end(c); ++b) {
    const double dx = x[static_cast<std::size_t>(bonds.neighbor(b))][0] - mid;
    CHECK(bonds.intact(b) == (std::abs(dx) < 0.5 * l0));
  }
  // The mirror image in x = mid: bond (i, j) is cut exactly when its image is.
  const auto image_of = [&](std::size_t i) {
    Vec<Dim> p = x[i];
    p[0] = 2 * mid - p[0];
    for (std::size_t j = 0; j < x.size(); ++j)
      if ((x[j] - p).norm() < 1e-9) return j;
    return x.size();
  };
  for (std::size_t i = 0; i < x.size(); ++i)
    for (Offset b = bonds.begin(i); b < bonds.end(i); ++b) {
      const std::size_t ii = image_of(i), jj = image_of(static_cast<std::size_t>(bonds.neighbor(b)));
      REQUIRE(ii < x.size());
      for (Offset e = bonds.begin(ii); e < bonds.end(ii); ++e)
        if (static_cast<std::size_t>(bonds.neighbor(e)) == jj) CHECK(bonds.intact(b) == bonds.intact(e));
    }
}

}
