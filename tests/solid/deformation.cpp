// SPDX-License-Identifier: BSD-3-Clause
#include <doctest/doctest.h>

#include <random>

#include <Eigen/Geometry>

#include "mpsfsi/kernels/weight.hpp"
#include "mpsfsi/scenes/solid_block.hpp"
#include "mpsfsi/solid/deformation.hpp"

using namespace mpsfsi;

namespace {

template <int Dim>
struct Block {
  ParticleSet<Dim> set;
  BondList<Dim> bonds;
  DeformationFit<Dim> fit;
  explicit Block(double l0) {
    Vec<Dim> upper = Vec<Dim>::Constant(6 * l0);
    set = scenes::material_block<Dim>(Vec<Dim>::Zero(), upper, l0);
    bonds.template build<KoshizukaWeight>(set.positions(), std::vector<std::int32_t>(set.size(), 0), 2.1 * l0);
    fit.build(bonds, l0);
  }
};

}  // namespace

TEST_SUITE("solid") {

TEST_CASE_TEMPLATE("solid.deformation: the fit reproduces affine and quadratic motion everywhere, surfaces included",
                   T, std::integral_constant<int, 2>, std::integral_constant<int, 3>) {
  constexpr int Dim = T::value;
  Block<Dim> block(0.01);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-0.3, 0.3);
  Mat<Dim> grad;
  for (int a = 0; a < Dim; ++a)
    for (int b = 0; b < Dim; ++b) grad(a, b) = (a == b ? 1.0 : 0.0) + u(rng);
  Vec<Dim> shift = Vec<Dim>::Constant(0.5);
  // x = shift + grad X + k (X . e0)^2 e1: a quadratic field; F(X) = grad + 2 k X_0 e1 e0^T.
  const double k = 3.0;
  VecArray<Dim> x(block.set.size());
  for (std::size_t i = 0; i < x.size(); ++i) {
    const Vec<Dim>& X = block.set.positions()[i];
    x[i] = shift + grad * X;
    x[i][1] += k * X[0] * X[0];
  }
  double worst = 0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    Mat<Dim> expect = grad;
    expect(1, 0) += 2 * k * block.set.positions()[i][0];
    worst = std::max(worst, (block.fit.gradient(x, block.bonds, i) - expect).cwiseAbs().maxCoeff());
  }
  CHECK(worst < 1e-10);
}

TEST_CASE_TEMPLATE("solid.deformation: gradient_at reads the fitted field's gradient away from the particle",
                   T, std::integral_constant<int, 2>, std::integral_constant<int, 3>) {
  constexpr int Dim = T::value;
  Block<Dim> block(0.01);
  // x = X + k (X_0 X_1, X_0^2 + X_1^2, ...): every component quadratic, so the second-order fit
  // is exact and its gradient at X_i + r must be the field's gradient there (linear in r).
  const double k = 2.0;
  const auto field_gradient = [&](const Vec<Dim>& X) {
    Mat<Dim> f = Mat<Dim>::Identity();
    f(0, 0) += k * X[1];
    f(0, 1) += k * X[0];
    f(1, 0) += 2 * k * X[0];
    f(1, 1) += 2 * k * X[1];
    return f;
  };
  VecArray<Dim> x(block.set.size());
  for (std::size_t i = 0; i < x.size(); ++i) {
    const Vec<Dim>& X = block.set.positions()[i];
    x[i] = X;
    x[i][0] += k * X[0] * X[1];
    x[i][1] += k * (X[0] * X[0] + X[1] * X[1]);
  }
  double worst = 0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    const Vec<Dim> r = Vec<Dim>::Constant(0.005);  // l0/2 out along the diagonal
    const Mat<Dim> f = block.fit.gradient_at(block.fit.affine(x, block.bonds, i), r);
    worst = std::max(worst, (f - field_gradient(block.set.positions()[i] + r)).cwiseAbs().maxCoeff());
  }
  CHECK(worst < 1e-10);
}

TEST_CASE("solid.deformation: a particle whose bonds span one direction stays undeformed across it") {
  ParticleSet<2> chain;
  for (int k = 0; k < 4; ++k) chain.add(Vec<2>(0.01 * k, 0));
  BondList<2> bonds;
  bonds.build<KoshizukaWeight>(chain.positions(), std::vector<std::int32_t>(4, 0), 0.021);
  DeformationFit<2> fit;
  fit.build(bonds, 0.01);
  VecArray<2> x = chain.positions();
  for (auto& p : x) p[0] *= 1.1;  // stretch along the chain
  const Mat<2> f = fit.gradient(x, bonds, 1);
  CHECK(f(0, 0) == doctest::Approx(1.1).epsilon(1e-12));
  CHECK(f(1, 1) == doctest::Approx(1.0).epsilon(1e-12));
  CHECK(f.allFinite());
}

TEST_CASE("solid.deformation: SVK stress is zero for rigid rotation and E eps for small uniaxial strain") {
  LameConstants<double> lame{1.0e6, 2.0e6};
  const Mat<2> rotation = Eigen::Rotation2D<double>(1.1).toRotationMatrix();
  CHECK(detail::cauchy_from_svk<2>(rotation, lame).norm() < 1e-9);
  Mat<2> f = Mat<2>::Identity();
  f(0, 0) += 1e-6;
  const Mat<2> sigma = detail::cauchy_from_svk<2>(f, lame);
  CHECK(sigma(0, 0) == doctest::Approx((lame.lambda + 2 * lame.mu) * 1e-6).epsilon(1e-5));
}

}
