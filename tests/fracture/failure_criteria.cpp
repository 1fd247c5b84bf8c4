// SPDX-License-Identifier: BSD-3-Clause
#include <doctest/doctest.h>

#include <algorithm>
#include <random>

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>

#include "mpsfsi/fracture/failure_criteria.hpp"

using namespace mpsfsi;

namespace {

Mat<2> tensor2(double sxx, double syy, double sxy) {
  Mat<2> s;
  s << sxx, sxy, sxy, syy;
  return s;
}

// |cos| of the angle between two directions (a plane normal has no sign).
template <int Dim>
double alignment(const Vec<Dim>& a, const Vec<Dim>& b) {
  return std::abs(a.normalized().dot(b.normalized()));
}

}  // namespace

TEST_SUITE("fracture") {

TEST_CASE_TEMPLATE("fracture.failure_criteria: known stress states give sigma_1 and its direction", C,
                   MaxPrincipalStress, MaxNormalStressAngle) {
  Vec<2> n;
  SUBCASE("uniaxial tension along x: vertical crack plane") {
    CHECK(C::template principal<2, double>(tensor2(3e6, 0, 0), n) == doctest::Approx(3e6));
    CHECK(alignment<2>(n, Vec<2>(1, 0)) == doctest::Approx(1.0));
  }
  SUBCASE("uniaxial tension along y") {
    CHECK(C::template principal<2, double>(tensor2(-1e6, 2e6, 0), n) == doctest::Approx(2e6));
    CHECK(alignment<2>(n, Vec<2>(0, 1)) == doctest::Approx(1.0));
  }
  SUBCASE("pure shear: sigma_1 = tau at 45 degrees") {
    CHECK(C::template principal<2, double>(tensor2(0, 0, 5e5), n) == doctest::Approx(5e5));
    CHECK(alignment<2>(n, Vec<2>(1, 1)) == doctest::Approx(1.0));
  }
  SUBCASE("isotropic tension: any direction") {
    CHECK(C::template principal<2, double>(tensor2(7e5, 7e5, 0), n) == doctest::Approx(7e5));
    CHECK(n.norm() == doctest::Approx(1.0));
  }
  SUBCASE("Mohr's circle") {
    const double sxx = 2e6, syy = -1e6, sxy = 1.5e6;
    const double expect = 0.5 * (sxx + syy) + std::hypot(0.5 * (sxx - syy), sxy);
    CHECK(C::template principal<2, double>(tensor2(sxx, syy, sxy), n) == doctest::Approx(expect).epsilon(1e-12));
    // The normal stress on the plane with normal n is sigma_1.
    CHECK(n.dot(tensor2(sxx, syy, sxy) * n) == doctest::Approx(expect).epsilon(1e-12));
  }
}

TEST_CASE("fracture.failure_criteria: the paper's angle solution and the eigen-decomposition agree") {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-3e6, 3e6);
  double worst_value = 0, worst_direction = 0;
  for (int k = 0; k < 2000; ++k) {
    const Mat<2> s = tensor2(u(rng), u(rng), u(rng));
    Vec<2> a, b;
    const double sa = MaxNormalStressAngle::principal<2, double>(s, a);
    const double sb = MaxPrincipalStress::principal<2, double>(s, b);
    worst_value = std::max(worst_value, std::abs(sa - sb) / s.norm());
    worst_direction = std::max(worst_direction, 1 - alignment<2>(a, b));
  }
  CHECK(worst_value < 1e-12);
  CHECK(worst_direction < 1e-8);
}

TEST_CASE_TEMPLATE("fracture.failure_criteria: invariant under rotation of the stress tensor", T,
                   std::integral_constant<int, 2>, std::integral_constant<int, 3>) {
  constexpr int Dim = T::value;
  std::mt19937 rng(9);
  std::uniform_real_distribution<double> u(-2e6, 2e6);
  for (int k = 0; k < 200; ++k) {
    Mat<Dim> s;
    for (int a = 0; a < Dim; ++a)
      for (int b = a; b < Dim; ++b) s(a, b) = s(b, a) = u(rng);
    Mat<Dim> r;
    if constexpr (Dim == 2) r = Eigen::Rotation2D<double>(u(rng) * 1e-6).toRotationMatrix();
    else r = Eigen::AngleAxisd(u(rng) * 1e-6, Vec<3>(u(rng), u(rng), u(rng)).normalized()).toRotationMatrix();
    Vec<Dim> n, nr;
    const double s1 = MaxPrincipalStress::principal<Dim, double>(s, n);
    const double s1r = MaxPrincipalStress::principal<Dim, double>(Mat<Dim>(r * s * r.transpose()), nr);
    CHECK(s1r == doctest::Approx(s1).epsilon(1e-12));
    CHECK(alignment<Dim>(nr, r * n) == doctest::Approx(1.0).epsilon(1e-6));
    if constexpr (Dim == 2) {
      Vec<2> m;
      CHECK(MaxNormalStressAngle::principal<2, double>(Mat<2>(r * s * r.transpose()), m) == doctest::Approx(s1).epsilon(1e-12));
    }
  }
}

// The crack-plane rule cuts on the normal's - side, so the sign of the direction decides which
// neighbour column a crack opens towards: it must follow one convention (first non-zero component
// positive) in both dimensions, and a 3D state that is a 2D one with a weaker z gives the 2D normal.
TEST_CASE("fracture.failure_criteria: the crack normal has the same sign convention in 2D and 3D") {
  std::mt19937 rng(13);
  std::uniform_real_distribution<double> u(-2e6, 2e6);
  int flipped_by_eigen = 0;
  for (int k = 0; k < 500; ++k) {
    const Mat<2> s2 = tensor2(u(rng), u(rng), u(rng));
    Mat<3> s3 = Mat<3>::Zero();
    s3.topLeftCorner<2, 2>() = s2;
    s3(2, 2) = -3e6;  // below every in-plane principal stress: sigma_1 lies in the plane
    Vec<2> n2;
    Vec<3> n3;
    const double a = MaxPrincipalStress::principal<2, double>(s2, n2);
    const double b = MaxPrincipalStress::principal<3, double>(s3, n3);
    CHECK(b == doctest::Approx(a).epsilon(1e-12));
    CHECK(n2[0] >= 0);
    CHECK(n3[0] >= 0);
    CHECK((n3 - Vec<3>(n2[0], n2[1], 0)).norm() < 1e-8);
    // A general 3D state: the first non-zero component is positive.
    Mat<3> g;
    for (int i = 0; i < 3; ++i)
      for (int j = i; j < 3; ++j) g(i, j) = g(j, i) = u(rng);
    MaxPrincipalStress::principal<3, double>(g, n3);
    CHECK(n3[0] > 0);
    for (const Mat<3>& t : {s3, g}) {
      Eigen::SelfAdjointEigenSolver<Mat<3>> eig(t);
      flipped_by_eigen += eig.eigenvectors().col(2)[0] < 0 ? 1 : 0;
    }
  }
  // Eigen's own sign is arbitrary: the convention is not vacuous.
  CHECK(flipped_by_eigen > 0);
  // Normals with a zero x component: the next component decides.
  Vec<3> n;
  MaxPrincipalStress::principal<3, double>(Mat<3>(Vec<3>(0, 2e6, 1e6).asDiagonal()), n);
  CHECK((n - Vec<3>(0, 1, 0)).norm() < 1e-12);
  MaxPrincipalStress::principal<3, double>(Mat<3>(Vec<3>(0, 1e6, 2e6).asDiagonal()), n);
  CHECK((n - Vec<3>(0, 0, 1)).norm() < 1e-12);
}

// The 3D closed form against Eigen's iterative self-adjoint solver: random tensors, and tensors
// with sigma_1 and sigma_2 1e-3, 1e-6 and 1e-8 of the principal stresses' spread apart (at 1e-8
// the direction within their plane is not defined to round-off, and only the residual is
// checked) or sigma_2 and sigma_3 1e-9 apart; exact double and triple roots, also rotated; a
// tensor of 1e-200 and one of 1e200. Bounds: round-off.
TEST_CASE("fracture.failure_criteria: the 3D closed form agrees with an iterative eigen-decomposition") {
  std::mt19937 rng(17);
  std::uniform_real_distribution<double> u(-2e6, 2e6);
  double worst_value = 0, worst_direction = 0, worst_residual = 0;
  for (int k = 0; k < 5000; ++k) {
    const double w = u(rng), x = u(rng), y = u(rng), z = u(rng);
    const Mat<3> q = Eigen::Quaterniond(w, x, y, z).normalized().toRotationMatrix();
    Vec<3> values;
    for (int i = 0; i < 3; ++i) values[i] = u(rng);
    std::sort(values.data(), values.data() + 3);
    const int family = k % 5;  // 0: random; 1-3: sigma_1 close to sigma_2; 4: sigma_2 close to sigma_3
    const double spread = values[2] - values[0];
    if (family >= 1 && family <= 3) values[1] = values[2] - std::pow(10.0, family == 3 ? -8.0 : -3.0 * family) * spread;
    if (family == 4) values[1] = values[0] + 1e-9 * spread;
    const Mat<3> s = q * values.asDiagonal() * q.transpose();
    Vec<3> n;
    const double s1 = MaxPrincipalStress::principal<3, double>(s, n);
    Eigen::SelfAdjointEigenSolver<Mat<3>> eig(s);
    worst_value = std::max(worst_value, std::abs(s1 - eig.eigenvalues()[2]) / s.norm());
    worst_residual = std::max(worst_residual, (s * n - s1 * n).norm() / s.norm());
    CHECK(n.norm() == doctest::Approx(1.0).epsilon(1e-12));
    if (family != 3) worst_direction = std::max(worst_direction, 1 - alignment<3>(n, eig.eigenvectors().col(2)));
  }
  CHECK(worst_value < 1e-14);
  CHECK(worst_residual < 1e-14);
  CHECK(worst_direction < 1e-12);
  SUBCASE("exact double and triple roots") {
    Vec<3> n;
    // Uniaxial compression: sigma_1 = 0 on the whole y-z plane.
    CHECK(std::abs(MaxPrincipalStress::principal<3, double>(Mat<3>(Vec<3>(-1e6, 0, 0).asDiagonal()), n)) < 1e-9);
    CHECK(std::abs(n[0]) < 1e-12);
    // Equibiaxial tension in x-z: sigma_1 = 2e6 with n in that plane.
    CHECK(MaxPrincipalStress::principal<3, double>(Mat<3>(Vec<3>(2e6, -1e6, 2e6).asDiagonal()), n) ==
          doctest::Approx(2e6).epsilon(1e-14));
    CHECK(std::abs(n[1]) < 1e-12);
    // The same, rotated: n in the rotated plane.
    const Mat<3> q = Eigen::AngleAxisd(0.7, Vec<3>(1, 2, 3).normalized()).toRotationMatrix();
    CHECK(MaxPrincipalStress::principal<3, double>(Mat<3>(q * Vec<3>(2e6, -1e6, 2e6).asDiagonal() * q.transpose()), n) ==
          doctest::Approx(2e6).epsilon(1e-14));
    CHECK(std::abs(n.dot(q.col(1))) < 1e-12);
    // Isotropic: any direction, x returned.
    CHECK(MaxPrincipalStress::principal<3, double>(Mat<3>(Mat<3>::Identity() * 5e5), n) == doctest::Approx(5e5).epsilon(1e-14));
    CHECK((n - Vec<3>::UnitX()).norm() == 0);
  }
  SUBCASE("scaled far from a stress's size") {
    const Mat<3> s = Mat<3>(Vec<3>(3, -1, 2).asDiagonal()) + Mat<3>::Constant(0.5);
    Vec<3> n, m;
    const double s1 = MaxPrincipalStress::principal<3, double>(s, n);
    for (const double factor : {1e-200, 1e200}) {
      CHECK(MaxPrincipalStress::principal<3, double>(Mat<3>(factor * s), m) == doctest::Approx(factor * s1).epsilon(1e-14));
      CHECK((m - n).norm() < 1e-14);
    }
  }
}

// MaxPrincipalStress::upper_bound, m + sqrt((d-1)/d) |dev|_F, is never below sigma_1 (random
// tensors, and sigma_1 close to sigma_2), and equals it in 2D (Mohr's radius) and in 3D when the
// two smaller principal stresses are equal (uniaxial tension), to within the bound's own
// round-off margin, 1e-12 (|m| + |dev|_F) <= 2e-12 |sigma|_F.
TEST_CASE("fracture.failure_criteria: the maximum principal stress's upper bound holds and is tight where it should be") {
  std::mt19937 rng(23);
  std::uniform_real_distribution<double> u(-2e6, 2e6);
  Vec<3> n3;
  Vec<2> n2;
  double worst_2d = 0, tightest_3d = 1e300;
  for (int k = 0; k < 5000; ++k) {
    const Mat<3> q = Eigen::Quaterniond(u(rng), u(rng), u(rng), u(rng)).normalized().toRotationMatrix();
    Vec<3> values(u(rng), u(rng), u(rng));
    if (k % 3 == 1) values[1] = values[0] * (1 - 1e-9);
    const Mat<3> s = q * values.asDiagonal() * q.transpose();
    const double s1 = MaxPrincipalStress::principal<3, double>(s, n3);
    const double bound = MaxPrincipalStress::upper_bound<3, double>(s);
    CHECK(bound >= s1);
    tightest_3d = std::min(tightest_3d, (bound - s1) / s.norm());
    const Mat<2> s2 = s.topLeftCorner<2, 2>();
    worst_2d = std::max(worst_2d, std::abs(MaxPrincipalStress::upper_bound<2, double>(s2) -
                                           MaxPrincipalStress::principal<2, double>(s2, n2)) / s2.norm());
  }
  CHECK(worst_2d < 2.5e-12);
  CHECK(tightest_3d >= 0);
  // Uniaxial tension along a rotated axis: sigma_2 = sigma_3 = 0 and the bound is sigma_1.
  const Mat<3> q = Eigen::AngleAxisd(0.4, Vec<3>(3, -1, 2).normalized()).toRotationMatrix();
  const Mat<3> uniaxial = q * Vec<3>(1.5e6, 0, 0).asDiagonal() * q.transpose();
  CHECK(MaxPrincipalStress::upper_bound<3, double>(uniaxial) == doctest::Approx(1.5e6).epsilon(2.5e-12));
}

TEST_CASE("fracture.failure_criteria: NoFailure never reaches any strength") {
  Vec<3> n;
  CHECK(NoFailure::principal<3, double>(Mat<3>::Identity() * 1e12, n) < -1e300);
  CHECK_FALSE(NoFailure::enabled);
}

}
