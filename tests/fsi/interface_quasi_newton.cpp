// SPDX-License-Identifier: BSD-3-Clause
#include <doctest/doctest.h>

#include <cmath>

#include <Eigen/Dense>

#include "mpsfsi/fsi/interface_quasi_newton.hpp"

using namespace mpsfsi;

namespace {

// A linear stand-in for the fluid's answer to a load, F~ = b + A F, with A = Q diag(g) Q^T for
// a fixed orthogonal Q: g = -30 is the added mass of a long heave mode (the floating beam's), the
// others weaker. Plain fixed-point iteration diverges (|g| > 1); the root is (I - A)^-1 b.
struct LinearInterface {
  static constexpr int particles = 4, n = 2 * particles;
  Eigen::MatrixXd a;
  LinearInterface() {
    const Eigen::MatrixXd q = Eigen::MatrixXd(Eigen::HouseholderQR<Eigen::MatrixXd>(Eigen::MatrixXd::Random(n, n)).householderQ());
    Eigen::VectorXd g(n);
    g << -30, -5, -1.5, -0.5, 0.2, 0.1, 0, 0.05;
    a = q * g.asDiagonal() * q.transpose();
  }
  // Iterates until |r| <= 1e-10 |F~| and returns the number of fluid answers used.
  int solve(InterfaceQuasiNewtonModel<>& model, const Eigen::VectorXd& b, VecArray<2>& load, int limit) const {
    model.begin_step();
    VecArray<2> trial(particles), residual(particles);
    for (int k = 1; k <= limit; ++k) {
      const Eigen::Map<const Eigen::VectorXd> f(load.data()->data(), n);
      const Eigen::VectorXd answer = b + a * f;
      for (int i = 0; i < particles; ++i) {
        trial[static_cast<std::size_t>(i)] = answer.segment<2>(2 * i);
        residual[static_cast<std::size_t>(i)] = trial[static_cast<std::size_t>(i)] - load[static_cast<std::size_t>(i)];
      }
      const Eigen::Map<const Eigen::VectorXd> r(residual.data()->data(), n);
      if (r.norm() <= 1e-10 * answer.norm()) return k;
      model.next_load(load, trial, residual, 0.02);
    }
    return limit + 1;
  }
  Eigen::VectorXd root(const Eigen::VectorXd& b) const {
    return (Eigen::MatrixXd::Identity(n, n) - a).partialPivLu().solve(b);
  }
};

double distance(const VecArray<2>& load, const Eigen::VectorXd& x) {
  return (Eigen::Map<const Eigen::VectorXd>(load.data()->data(), static_cast<Eigen::Index>(2 * load.size())) - x).norm() /
         x.norm();
}

}  // namespace

TEST_SUITE("fsi") {

// IQN-ILS on a linear map is a Krylov method (Degroote et al. 2009): it finds the root within
// n + 1 answers in exact arithmetic, here n = 8 unknowns, and round-off adds a few.
TEST_CASE("fsi.interface_quasi_newton: the root of a linear interface that the fixed point cannot reach") {
  const LinearInterface lin;
  const Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(LinearInterface::n, 1.0, 2.0);
  InterfaceQuasiNewtonModel<> model(0);
  VecArray<2> load(LinearInterface::particles, Vec<2>::Zero());
  const int answers = lin.solve(model, b, load, 30);
  MESSAGE("IQN-ILS: " << answers << " answers for 8 unknowns");
  CHECK(answers <= LinearInterface::n + 3);
  CHECK(distance(load, lin.root(b)) < 1e-8);
}

// With the columns of earlier steps kept, the model already holds the map's inverse Jacobian:
// the next step, a different right-hand side on the same map, needs a single correction.
TEST_CASE("fsi.interface_quasi_newton: columns reused from the last step make the next one Newton") {
  const LinearInterface lin;
  InterfaceQuasiNewtonModel<> with_reuse(1), without_reuse(0);
  const Eigen::VectorXd b1 = Eigen::VectorXd::LinSpaced(LinearInterface::n, 1.0, 2.0);
  const Eigen::VectorXd b2 = Eigen::VectorXd::LinSpaced(LinearInterface::n, 2.0, -1.0);
  VecArray<2> load(LinearInterface::particles, Vec<2>::Zero()), fresh = load;
  REQUIRE(lin.solve(with_reuse, b1, load, 30) <= LinearInterface::n + 3);
  REQUIRE(lin.solve(without_reuse, b1, fresh, 30) <= LinearInterface::n + 3);
  const int reused = lin.solve(with_reuse, b2, load, 30), not_reused = lin.solve(without_reuse, b2, fresh, 30);
  MESSAGE("second step: " << reused << " answers with reuse, " << not_reused << " without");
  CHECK(reused <= 3);
  CHECK(not_reused > reused);
  CHECK(distance(load, lin.root(b2)) < 1e-8);
}

}
