// SPDX-License-Identifier: BSD-3-Clause
#include <doctest/doctest.h>

#include <random>

#include <Eigen/Geometry>

#include "mpsfsi/core/parallel.hpp"
#include "mpsfsi/kernels/lattice_constants.hpp"
#include "mpsfsi/kernels/weight.hpp"
#include "mpsfsi/scenes/solid_block.hpp"
#include "mpsfsi/solid/bond_viscosity.hpp"
#include "mpsfsi/solid/corrected_total_lagrangian.hpp"
#include "mpsfsi/solid/hwang_model.hpp"
#include "mpsfsi/solid/policy_checks.hpp"

using namespace mpsfsi;

namespace {

template <int Dim, class Model>
struct ModelBlock {
  ParticleSet<Dim> set;
  BondList<Dim> bonds;
  Model model;
  SolidModelContext<Dim> context;
  ModelBlock(double l0, int cells_x, int cells_y, const LameConstants<double>& lame, int cells_z = 4) {
    Vec<Dim> upper = Vec<Dim>::Constant(cells_z * l0);
    upper[0] = cells_x * l0;
    upper[1] = cells_y * l0;
    set = scenes::material_block<Dim>(Vec<Dim>::Zero(), upper, l0);
    bonds.template build<KoshizukaWeight>(set.positions(), std::vector<std::int32_t>(set.size(), 0), 2.1 * l0);
    const auto c = ideal_lattice_constants<Dim, KoshizukaWeight>(l0, 2.1 * l0);
    context = SolidModelContext<Dim>{lame, 1000.0, l0, std::pow(l0, Dim), c.n0, c.lambda};
    model.initialize(bonds, context);
  }
};

const LameConstants<double> kLame{1.5e6, 1.0e6};

// A rigid motion of the block (rotation, then a shift): no force and no stress, to round-off.
template <int Dim>
void check_no_force_no_stress(ModelBlock<Dim, CorrectedTotalLagrangian<Dim>>& block, const Mat<Dim>& rotation) {
  VecArray<Dim> x = block.set.positions();
  for (auto& p : x) p = rotation * p + Vec<Dim>::Constant(0.2);
  VecArray<Dim> f;
  block.model.internal_forces(x, block.bonds, f);
  MatArray<Dim> sigma;
  block.model.stresses(x, block.bonds, sigma);
  double worst_f = 0, worst_s = 0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    worst_f = std::max(worst_f, f[i].norm());
    worst_s = std::max(worst_s, sigma[i].norm());
  }
  CHECK(worst_f < 1e-10 * kLame.mu * std::pow(block.context.l0, Dim - 1));
  CHECK(worst_s < 1e-10 * kLame.mu);
}

template <int Dim>
Mat<Dim> test_rotation() {
  if constexpr (Dim == 2) return Eigen::Rotation2D<double>(0.6).toRotationMatrix();
  else return Eigen::AngleAxisd(0.6, Vec<3>(1, 2, 3).normalized()).toRotationMatrix();
}

// The force loop against a plain sum over directed bonds, t_ij = V P_i g_ij + 2c beta_ij delta_ij
// added to i and subtracted from j (for a particle that reads softly, V P_i with the stabilisation's
// residual and the turn's term, DeformationFit::objective_stress_term), with the model's own fit, on 1, 2 and 3 threads; the loop
// that also gives the stresses gives the same forces, the stresses of the fit's F to round-off,
// and those of stresses() to the bit; the loop with the bond viscosity gives the forces plus
// BondViscosity's to round-off, at random velocities, with and without the stresses.
template <int Dim>
void check_force_loop_against_bond_sum(ModelBlock<Dim, CorrectedTotalLagrangian<Dim>>& block, const VecArray<Dim>& x) {
  VecArray<Dim> velocity(x.size());
  std::mt19937 rng(17);
  std::uniform_real_distribution<double> speed(-0.1, 0.1);
  for (auto& p : velocity)
    for (int a = 0; a < Dim; ++a) p[a] = speed(rng);
  BondViscosity<Dim> viscosity;
  viscosity.initialize(block.bonds);
  const auto& fit = block.model.fit();
  const double c2 = 2 * block.model.stabilization * kLame.mu * block.context.volume * Dim / block.context.n0;
  VecArray<Dim> reference(x.size(), Vec<Dim>::Zero());
  for (std::size_t i = 0; i < x.size(); ++i) {
    const auto a = fit.affine(x, block.bonds, i);
    const Mat<Dim> fi = a.template leftCols<Dim>();
    Mat<Dim> vp = block.context.volume * fi * detail::svk_stress(detail::green_strain(fi), kLame);
    if (fit.reads_softly(i)) {
      // The fit as the bonds give it (before the turn), and the stabilisation's residual
      // R = sum_j beta_ij delta_ij r0_ij^T, which the turned, floored fit leaves.
      Mat<Dim> fitted = Mat<Dim>::Identity(), residual = Mat<Dim>::Zero();
      for (Offset b = block.bonds.begin(i); b < block.bonds.end(i); ++b) {
        const auto j = static_cast<std::size_t>(block.bonds.neighbor(b));
        const Vec<Dim>& r0 = block.bonds.r0(b);
        fitted += (x[j] - x[i] - r0) * fit.gradient_coefficient(b).transpose();
        residual += block.bonds.beta(b) * (x[j] - x[i] - a * fit.basis(r0)) * r0.transpose();
      }
      const Mat<Dim> pull = vp - c2 * residual;
      vp = pull + fit.objective_stress_term(fitted, pull, i);
    }
    for (Offset b = block.bonds.begin(i); b < block.bonds.end(i); ++b) {
      const auto j = static_cast<std::size_t>(block.bonds.neighbor(b));
      const auto& g = fit.coefficients()[static_cast<std::size_t>(b)];
      const Vec<Dim> delta = x[j] - x[i] - a * fit.basis(block.bonds.r0(b));
      const Vec<Dim> t = vp * g.template head<Dim>() + c2 * block.bonds.beta(b) * delta;
      reference[i] += t;
      reference[j] -= t;
    }
  }
  double scale = 0;
  for (const auto& r : reference) scale = std::max(scale, r.norm());
  CHECK(scale > 0);
  MatArray<Dim> expected_stress;
  detail::fitted_cauchy_stresses(fit, x, block.bonds, kLame, expected_stress);
  double stress_scale = 0;
  for (const auto& s : expected_stress) stress_scale = std::max(stress_scale, s.norm());
  CHECK(stress_scale > 0);
  // A viscosity coefficient that makes the viscous forces as large as the elastic ones.
  VecArray<Dim> unit_viscous(x.size(), Vec<Dim>::Zero());
  viscosity.add(block.bonds, x, velocity, 1.0, unit_viscous);
  double unit_scale = 0;
  for (const auto& f : unit_viscous) unit_scale = std::max(unit_scale, f.norm());
  REQUIRE(unit_scale > 0);
  const double zeta = scale / unit_scale;
  const int saved = parallel::max_threads();
  for (int threads = 1; threads <= 3; ++threads) {
    CAPTURE(threads);
    parallel::set_num_threads(threads);
    VecArray<Dim> f;
    block.model.internal_forces(x, block.bonds, f);
    double worst = 0;
    for (std::size_t i = 0; i < x.size(); ++i) {
      REQUIRE(f[i].allFinite());
      REQUIRE(reference[i].allFinite());
      worst = std::max(worst, (f[i] - reference[i]).norm());
    }
    CHECK(worst < 1e-12 * scale);
    VecArray<Dim> f_with_stress;
    MatArray<Dim> stress;
    block.model.internal_forces(x, block.bonds, f_with_stress, stress);
    REQUIRE(stress.size() == x.size());
    MatArray<Dim> on_demand;
    block.model.stresses(x, block.bonds, on_demand);
    double worst_stress = 0;
    for (std::size_t i = 0; i < x.size(); ++i) {
      CHECK(f_with_stress[i] == f[i]);  // the same loop
      CHECK(on_demand[i] == stress[i]);
      worst_stress = std::max(worst_stress, (stress[i] - expected_stress[i]).norm());
    }
    CHECK(worst_stress < 1e-12 * stress_scale);
    VecArray<Dim> with_viscosity = f;
    viscosity.add(block.bonds, x, velocity, zeta, with_viscosity);
    double viscous_scale = 0;
    for (std::size_t i = 0; i < x.size(); ++i) viscous_scale = std::max(viscous_scale, (with_viscosity[i] - f[i]).norm());
    CHECK(viscous_scale > 0.5 * scale);
    VecArray<Dim> fused, fused_with_stress;
    MatArray<Dim> fused_stress;
    block.model.internal_forces(x, velocity, block.bonds, fused, nullptr, zeta);
    block.model.internal_forces(x, velocity, block.bonds, fused_with_stress, &fused_stress, zeta);
    double worst_fused = 0, worst_fused_stress = 0;
    for (std::size_t i = 0; i < x.size(); ++i) {
      worst_fused = std::max(worst_fused, (fused[i] - with_viscosity[i]).norm());
      CHECK(fused_with_stress[i] == fused[i]);  // the same instantiation of the loop
      worst_fused_stress = std::max(worst_fused_stress, (fused_stress[i] - stress[i]).norm());
    }
    CHECK(worst_fused < 1e-12 * scale);
    CHECK(worst_fused_stress < 1e-12 * stress_scale);  // another instantiation: round-off
    // Kept fits (for the failure check's surface read): two particles in three asked for. They
    // are DeformationFit::affine's A_i to round-off (the same sums in another order), and keeping
    // them changes no force.
    std::vector<std::uint8_t> wanted(x.size());
    for (std::size_t i = 0; i < x.size(); ++i) wanted[i] = i % 3 != 2 ? 1 : 0;
    block.model.keep_affine(&wanted);
    REQUIRE(block.model.keeps_affine(x.size()));
    VecArray<Dim> keeping;
    MatArray<Dim> keeping_stress;
    block.model.internal_forces(x, velocity, block.bonds, keeping, &keeping_stress, zeta);
    CHECK(!block.model.keeps_affine(x.size()));  // for one loop only
    const auto& kept = block.model.kept_affine();
    REQUIRE(kept.size() == x.size());
    double worst_affine = 0, affine_scale = 0;
    for (std::size_t i = 0; i < x.size(); ++i) {
      CHECK(keeping[i] == fused_with_stress[i]);
      CHECK(keeping_stress[i] == fused_stress[i]);
      if (!wanted[i]) continue;
      const auto expected = fit.affine(x, block.bonds, i);
      affine_scale = std::max(affine_scale, expected.norm());
      worst_affine = std::max(worst_affine, (kept[i] - expected).norm());
    }
    CHECK(affine_scale > 0);
    CHECK(worst_affine < 1e-12 * affine_scale);
  }
  parallel::set_num_threads(saved);
}

}  // namespace

// ElasticSolver takes the fused pass only if the default model's overload matches the trait.
static_assert(detail::has_model_forces_with_viscosity<CorrectedTotalLagrangian<2>, 2>::value);
static_assert(detail::has_model_forces_with_viscosity<CorrectedTotalLagrangian<3>, 3>::value);
static_assert(!detail::has_model_forces_with_viscosity<HwangModel<2>, 2>::value);

TEST_SUITE("solid") {

TEST_CASE_TEMPLATE("solid.stress_models: no force and no stress under rigid translation", Model,
                   CorrectedTotalLagrangian<2>, HwangModel<2>) {
  ModelBlock<2, Model> block(0.01, 8, 6, kLame);
  VecArray<2> x = block.set.positions();
  for (auto& p : x) p += Vec<2>(0.3, -0.7);
  VecArray<2> f;
  block.model.internal_forces(x, block.bonds, f);
  MatArray<2> sigma;
  block.model.stresses(x, block.bonds, sigma);
  for (std::size_t i = 0; i < x.size(); ++i) {
    CHECK(f[i].norm() < 1e-9 * kLame.mu * 0.01);
    CHECK(sigma[i].norm() < 1e-9 * kLame.mu);
  }
}

TEST_CASE_TEMPLATE("solid.corrected_total_lagrangian: rigid rotation by 90 degrees gives no force and no stress", T,
                   std::integral_constant<int, 2>, std::integral_constant<int, 3>) {
  constexpr int Dim = T::value;
  ModelBlock<Dim, CorrectedTotalLagrangian<Dim>> block(0.01, 7, 5, kLame);
  Mat<Dim> rotation = Mat<Dim>::Identity();
  if constexpr (Dim == 2) rotation = Eigen::Rotation2D<double>(M_PI / 2).toRotationMatrix();
  else rotation = Eigen::AngleAxisd(M_PI / 2, Vec<3>(1, 2, 3).normalized()).toRotationMatrix();
  check_no_force_no_stress(block, rotation);
}

TEST_CASE_TEMPLATE("solid.stress_models: forces conserve momentum under an arbitrary deformation", Model,
                   CorrectedTotalLagrangian<2>, HwangModel<2>) {
  ModelBlock<2, Model> block(0.01, 8, 6, kLame);
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-0.002, 0.002);
  VecArray<2> x = block.set.positions();
  for (auto& p : x) p += Vec<2>(u(rng), u(rng));
  VecArray<2> f;
  block.model.internal_forces(x, block.bonds, f);
  Vec<2> total = Vec<2>::Zero();
  double torque = 0, scale = 0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    total += f[i];
    torque += x[i][0] * f[i][1] - x[i][1] * f[i][0];
    scale += f[i].norm();
  }
  CHECK(total.norm() < 1e-12 * scale);
  // The corrected model's forces are central in sum (angular momentum); the paper's model
  // returns the missing torque through particle spin instead, so only linear momentum here.
  if constexpr (std::is_same_v<Model, CorrectedTotalLagrangian<2>>) CHECK(std::abs(torque) < 1e-12 * scale);
}

TEST_CASE("solid.corrected_total_lagrangian: forces are the negative gradient of the strain energy") {
  ModelBlock<2, CorrectedTotalLagrangian<2>> block(0.01, 6, 5, kLame);
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-0.001, 0.001);
  VecArray<2> x = block.set.positions();
  for (auto& p : x) p += Vec<2>(u(rng), u(rng));
  VecArray<2> f;
  block.model.internal_forces(x, block.bonds, f);
  const double h = 1e-7;
  double worst = 0, scale = 0;
  for (std::size_t i : {0ul, 7ul, 14ul, 29ul}) {
    for (int a = 0; a < 2; ++a) {
      VecArray<2> xp = x, xm = x;
      xp[i][a] += h;
      xm[i][a] -= h;
      const double numeric = -(block.model.strain_energy(xp, block.bonds) - block.model.strain_energy(xm, block.bonds)) / (2 * h);
      worst = std::max(worst, std::abs(numeric - f[i][a]));
      scale = std::max(scale, std::abs(f[i][a]));
    }
  }
  CHECK(worst < 1e-5 * scale);  // central differences: truncation ~h^2, round-off ~1e-16 U / h
}

// The particle at lattice site `site` (the block's particles sit at (site + 1/2) l0).
template <int Dim>
std::size_t particle_at_site(const ModelBlock<Dim, CorrectedTotalLagrangian<Dim>>& block, const Vec<Dim>& site) {
  const auto& x0 = block.set.positions();
  for (std::size_t i = 0; i < x0.size(); ++i)
    if ((x0[i] - (site + Vec<Dim>::Constant(0.5)) * block.context.l0).norm() < 1e-9) return i;
  FAIL("no particle at the lattice site");
  return 0;
}

// Cuts every bond of particle i whose reference vector (in units of l0) `keep` rejects; returns
// the particles to refit.
template <int Dim, class Keep>
std::vector<std::size_t> cut_all_but(ModelBlock<Dim, CorrectedTotalLagrangian<Dim>>& block, std::size_t i, Keep keep) {
  std::vector<std::size_t> touched;
  for (Offset b = block.bonds.begin(i); b < block.bonds.end(i); ++b)
    if (!keep(Vec<Dim>(block.bonds.r0(b) / block.context.l0)) && block.bonds.cut(b)) {
      touched.push_back(i);
      touched.push_back(static_cast<std::size_t>(block.bonds.neighbor(b)));
    }
  return touched;
}

// The forces at `particles` and a bond partner of each against central differences of the energy,
// in the block rotated and disturbed by 1 % of l0.
template <int Dim>
void check_forces_are_energy_gradient(ModelBlock<Dim, CorrectedTotalLagrangian<Dim>>& block,
                                      const std::vector<std::size_t>& particles) {
  std::mt19937 rng(23);
  const double l0 = block.context.l0;
  std::uniform_real_distribution<double> u(-0.01 * l0, 0.01 * l0);
  VecArray<Dim> x = block.set.positions();
  for (auto& p : x) {
    p = test_rotation<Dim>() * p + Vec<Dim>::Constant(0.2);
    for (int a = 0; a < Dim; ++a) p[a] += u(rng);
  }
  VecArray<Dim> f;
  block.model.internal_forces(x, block.bonds, f);
  const double h = 1e-7;
  double worst = 0, scale = 0;
  for (const std::size_t particle : particles)
    for (const std::size_t i : {particle, particle + 1})
      for (int a = 0; a < Dim; ++a) {
        VecArray<Dim> xp = x, xm = x;
        xp[i][a] += h;
        xm[i][a] -= h;
        const double numeric =
            -(block.model.strain_energy(xp, block.bonds) - block.model.strain_energy(xm, block.bonds)) / (2 * h);
        worst = std::max(worst, std::abs(numeric - f[i][a]));
        scale = std::max(scale, std::abs(f[i][a]));
      }
  CHECK(worst < 1e-5 * scale);  // central differences, as in the intact block's test above
}

// Cutting can leave a particle bonded along one line (a slab cut beside it) or, in 3D, in one
// plane; its F then turns across the bonds with them (DeformationFit::objective). A rigid
// rotation of the body must still give no force and no stress (with F = I across the bonds it
// read as shear mu theta there), and the forces must stay the exact negative gradient of the energy.
TEST_CASE_TEMPLATE("solid.corrected_total_lagrangian: a particle left with a line or a plane of bonds: rigid rotation "
                   "gives no stress, the forces are the energy's gradient",
                   T, std::integral_constant<int, 2>, std::integral_constant<int, 3>) {
  constexpr int Dim = T::value;
  ModelBlock<Dim, CorrectedTotalLagrangian<Dim>> block(0.01, 9, 5, kLame, 4);
  // `line` keeps its bonds along x; in 3D `plane` (4 spacings away, no common bond) those in z = const.
  Vec<Dim> line_site = Vec<Dim>::Constant(2), plane_site = Vec<Dim>::Constant(2);
  plane_site[0] = 6;
  const std::size_t line = particle_at_site(block, line_site);
  const std::size_t plane = Dim == 3 ? particle_at_site(block, plane_site) : line;
  auto touched = cut_all_but(block, line, [](const Vec<Dim>& r) { return r.tail(Dim - 1).norm() < 1e-9; });
  if (Dim == 3) {
    const auto more = cut_all_but(block, plane, [](const Vec<Dim>& r) { return std::abs(r[Dim - 1]) < 1e-9; });
    touched.insert(touched.end(), more.begin(), more.end());
  }
  block.model.bonds_changed(block.bonds, touched);
  REQUIRE(block.model.fit().has_free_direction(line));
  REQUIRE(block.model.fit().has_free_direction(plane));
  check_no_force_no_stress(block, test_rotation<Dim>());
  check_forces_are_energy_gradient(block, {line, plane});
}

// A particle whose bonds resolve every direction but some only weakly (below the floor) reads
// them softly; the share of F its bonds do not set turns with the bonded directions
// (DeformationFit::objective). Kept: the bonds along x and one diagonal bond (2D: y weak); in 3D
// the bonds in z = 0 and one out of it (z weak, the plane turn), or the bonds along x and one
// diagonal into y and one into z (y and z weak, the frame turn). A rigid rotation gives no force
// and no stress, the forces are the energy's gradient and equal the bond-by-bond sum.
TEST_CASE_TEMPLATE("solid.corrected_total_lagrangian: a particle that reads a direction softly: rigid rotation gives "
                   "no stress, the forces are the energy's gradient",
                   T, std::integral_constant<int, 2>, std::integral_constant<int, 3>) {
  constexpr int Dim = T::value;
  for (const bool frame : {false, true}) {
    if (Dim == 2 && frame) continue;
    CAPTURE(frame);
    ModelBlock<Dim, CorrectedTotalLagrangian<Dim>> block(0.01, 9, 5, kLame, 5);
    const std::size_t soft = particle_at_site(block, Vec<Dim>(Vec<Dim>::Constant(2)));
    const auto keep = [frame](const Vec<Dim>& r) {
      Vec<Dim> diagonal = Vec<Dim>::Zero();
      diagonal[0] = diagonal[1] = 1;
      if (Dim == 2 || frame) {
        if ((r - diagonal).norm() < 1e-9 || r.tail(Dim - 1).norm() < 1e-9) return true;
        Vec<Dim> into_z = Vec<Dim>::Zero();
        into_z[0] = into_z[Dim - 1] = 1;
        return Dim == 3 && (r - into_z).norm() < 1e-9;
      }
      Vec<Dim> out_of_plane = diagonal;
      out_of_plane[1] = 0;
      out_of_plane[Dim - 1] = 1;
      return std::abs(r[Dim - 1]) < 1e-9 || (r - out_of_plane).norm() < 1e-9;
    };
    block.model.bonds_changed(block.bonds, cut_all_but(block, soft, keep));
    REQUIRE(block.model.fit().reads_softly(soft));
    REQUIRE_FALSE(block.model.fit().has_free_direction(soft));
    check_no_force_no_stress(block, test_rotation<Dim>());
    check_forces_are_energy_gradient(block, {soft});
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> u(-0.05 * block.context.l0, 0.05 * block.context.l0);
    VecArray<Dim> x = block.set.positions();
    for (auto& p : x) {
      p = test_rotation<Dim>() * p;
      for (int a = 0; a < Dim; ++a) p[a] += u(rng) + 0.02 * p[0];
    }
    check_force_loop_against_bond_sum(block, x);
  }
}

// The force loop works from r0, beta and each particle's M_i^+ (detail::PackedBonds), a group of
// particles per SIMD register; here it is checked against the forces written out bond by bond
// from the fit coefficients g_ij,
//   f_k = sum_j (t_kj - t_jk),  t_ij = V P_i g_ij + 2c beta_ij (r_ij - A_i phi(r0_ij)),
// after a crack has cut bonds (some particles then fall back to the linear fit). The particle
// count is odd, so the last group has empty lanes, and 1 to 3 threads split the groups. Agreement
// to round-off: the two differ only in the order of the sums.
TEST_CASE_TEMPLATE("solid.corrected_total_lagrangian: force loop equals the bond-by-bond sum, with cut bonds", T,
                   std::integral_constant<int, 2>, std::integral_constant<int, 3>) {
  constexpr int Dim = T::value;
  const double l0 = 0.01;
  ModelBlock<Dim, CorrectedTotalLagrangian<Dim>> block(l0, 9, 5, kLame, 3);
  REQUIRE(block.set.size() % 2 == 1);
  // Cut every bond crossing x = 4.5 l0 below y = 3.5 l0 (a notch), and refit the particles.
  std::vector<std::size_t> touched;
  const auto& x0 = block.set.positions();
  for (std::size_t i = 0; i < x0.size(); ++i)
    for (Offset b = block.bonds.begin(i); b < block.bonds.end(i); ++b) {
      const auto j = static_cast<std::size_t>(block.bonds.neighbor(b));
      const bool across = (x0[i][0] < 4.5 * l0) != (x0[j][0] < 4.5 * l0);
      if (across && x0[i][1] < 3.5 * l0 && x0[j][1] < 3.5 * l0 && block.bonds.cut(b)) {
        touched.push_back(i);
        touched.push_back(j);
      }
    }
  REQUIRE(block.bonds.num_cut() > 0);
  block.model.bonds_changed(block.bonds, touched);
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-0.05 * l0, 0.05 * l0);
  VecArray<Dim> x = x0;
  for (auto& p : x)
    for (int a = 0; a < Dim; ++a) p[a] += u(rng) + 0.02 * p[0];  // noise plus a 2 % affine deformation

  check_force_loop_against_bond_sum(block, x);
}

// Heavy damage, as behind a running crack: a random 60 % of the bonds cut, and every bond of
// two particles (chips), so that some particles keep too few bonds for a full-rank fit.
TEST_CASE_TEMPLATE("solid.corrected_total_lagrangian: force loop equals the bond-by-bond sum after heavy damage", T,
                   std::integral_constant<int, 2>, std::integral_constant<int, 3>) {
  constexpr int Dim = T::value;
  const double l0 = 0.01;
  ModelBlock<Dim, CorrectedTotalLagrangian<Dim>> block(l0, 9, 5, kLame, 3);
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> coin(0, 1);
  std::vector<std::size_t> touched;
  const std::size_t chips[] = {7, block.set.size() / 2};
  for (std::size_t i = 0; i < block.set.size(); ++i)
    for (Offset b = block.bonds.begin(i); b < block.bonds.end(i); ++b) {
      const auto j = static_cast<std::size_t>(block.bonds.neighbor(b));
      const bool chip = i == chips[0] || i == chips[1] || j == chips[0] || j == chips[1];
      if (j > i && (chip || coin(rng) < 0.6) && block.bonds.cut(b)) {
        touched.push_back(i);
        touched.push_back(j);
      }
    }
  REQUIRE(block.bonds.intact_count(chips[0]) == 0);
  REQUIRE(block.bonds.intact_count(chips[1]) == 0);
  block.model.bonds_changed(block.bonds, touched);
  std::uniform_real_distribution<double> u(-0.05 * l0, 0.05 * l0);
  VecArray<Dim> x = block.set.positions();
  for (auto& p : x)
    for (int a = 0; a < Dim; ++a) p[a] += u(rng) + 0.02 * p[0];
  check_force_loop_against_bond_sum(block, x);
}

// Fewer groups of particles than threads: a row of 3 particles is one group, so on 3 and 8
// threads most threads have no particles, and every force copy spans the whole (short) array.
// The forces must be those of one thread to round-off, and sum to zero (momentum).
TEST_CASE("solid.corrected_total_lagrangian: force loop with fewer particle groups than threads") {
  const double l0 = 0.01;
  ModelBlock<2, CorrectedTotalLagrangian<2>> block(l0, 3, 1, kLame);
  REQUIRE(block.set.size() == 3);
  VecArray<2> x = block.set.positions();
  x[0] += Vec<2>(-0.02 * l0, 0.01 * l0);
  x[2] += Vec<2>(0.03 * l0, -0.01 * l0);
  const int saved = parallel::max_threads();
  parallel::set_num_threads(1);
  VecArray<2> one;
  block.model.internal_forces(x, block.bonds, one);
  double scale = 0;
  for (const auto& f : one) scale = std::max(scale, f.norm());
  CHECK(scale > 0);
  CHECK((one[0] + one[1] + one[2]).norm() < 1e-12 * scale);
  for (const int threads : {3, 8}) {
    CAPTURE(threads);
    parallel::set_num_threads(threads);
    VecArray<2> f;
    block.model.internal_forces(x, block.bonds, f);
    REQUIRE(f.size() == 3);
    for (std::size_t i = 0; i < 3; ++i) CHECK((f[i] - one[i]).norm() < 1e-12 * scale);
  }
  parallel::set_num_threads(saved);
}

TEST_CASE_TEMPLATE("solid.stress_models: patch test, uniform uniaxial stress in plane stress", Model,
                   CorrectedTotalLagrangian<2>, HwangModel<2>) {
  // Plane stress lambda* = 2 lambda mu / (lambda + 2 mu); E and nu from the 3D constants.
  const double e = kLame.mu * (3 * kLame.lambda + 2 * kLame.mu) / (kLame.lambda + kLame.mu);
  const double nu = kLame.lambda / (2 * (kLame.lambda + kLame.mu));
  const LameConstants<double> plane{2 * kLame.lambda * kLame.mu / (kLame.lambda + 2 * kLame.mu), kLame.mu};
  ModelBlock<2, Model> block(0.01, 20, 8, plane);
  const double eps = 1e-5;
  VecArray<2> x = block.set.positions();
  for (auto& p : x) p = Vec<2>(p[0] * (1 + eps), p[1] * (1 - nu * eps));
  VecArray<2> f;
  block.model.internal_forces(x, block.bonds, f);
  MatArray<2> sigma;
  block.model.stresses(x, block.bonds, sigma);
  double worst_stress = 0, worst_force = 0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    const Vec<2>& X = block.set.positions()[i];
    if (X[0] < 0.03 || X[0] > 0.17) continue;  // away from the loaded ends; top and bottom included
    worst_stress = std::max(worst_stress, std::abs(sigma[i](0, 0) / (e * eps) - 1));
    worst_stress = std::max(worst_stress, std::abs(sigma[i](1, 1)) / (e * eps));
    // Forces need the neighbours' neighbours (2 re) to be clear of the loaded ends as well.
    if (X[0] > 0.05 && X[0] < 0.15) worst_force = std::max(worst_force, f[i].norm() / (e * eps * 0.01));
  }
  MESSAGE(std::string(Model::name) << ": interior stress error " << worst_stress << ", residual force / (sigma l0) " << worst_force);
  // 1 % of the analytic uniform stress; both models measure 1.9e-5, the St Venant-Kirchhoff law's
  // own nonlinearity at this strain (docs/validation/solid.md).
  CHECK(worst_stress < 0.01);
  // The corrected model is in equilibrium under uniform stress, free surfaces included, up to
  // the St Venant-Kirchhoff law's own nonlinearity (sigma_yy = O(eps^2) E, i.e. 1e-5 relative).
  if constexpr (std::is_same_v<Model, CorrectedTotalLagrangian<2>>) CHECK(worst_force < 1e-4);
}

}
