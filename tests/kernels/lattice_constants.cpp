// SPDX-License-Identifier: BSD-3-Clause
#include <doctest/doctest.h>

#include <cmath>

#include "mpsfsi/kernels/lattice_constants.hpp"

using namespace mpsfsi;

TEST_SUITE("kernels") {

TEST_CASE("kernels.lattice_constants: n0 and lambda by hand for re = 2.1 l0 in 2D") {
  // Neighbours within 2.1 l0 on the square lattice: 4 at l0, 4 at sqrt(2) l0, 4 at 2 l0.
  const double l0 = 0.01, re = 2.1 * l0;
  const auto c = ideal_lattice_constants<2, KoshizukaWeight>(l0, re);
  const double w1 = 2.1 - 1, w2 = 2.1 / std::sqrt(2.0) - 1, w3 = 2.1 / 2 - 1;
  const double n0 = 4 * (w1 + w2 + w3);
  CHECK(std::abs(c.n0 - n0) < 1e-14 * n0);
  const double lambda = 4 * (w1 * 1 + w2 * 2 + w3 * 4) * l0 * l0 / n0;
  CHECK(std::abs(c.lambda - lambda) < 1e-14 * lambda);
}

TEST_CASE("kernels.lattice_constants: rejects re <= l0 and non-positive spacing") {
  CHECK_THROWS_AS((ideal_lattice_constants<2, KoshizukaWeight>(1.0, 1.0)), InvalidInput);
  CHECK_THROWS_AS((ideal_lattice_constants<3, KoshizukaWeight>(0.0, 1.0)), InvalidInput);
  CHECK_THROWS_AS((ideal_lattice_constants<3, WendlandC2Weight>(-1.0, 1.0)), InvalidInput);
}

}  // TEST_SUITE
