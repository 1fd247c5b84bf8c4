// SPDX-License-Identifier: BSD-3-Clause
#include <doctest/doctest.h>

#include "mpsfsi/kernels/weight.hpp"

using namespace mpsfsi;

TEST_SUITE("kernels") {

TEST_CASE("kernels.weight: Koshizuka weight is eq 13 with a guard at r -> 0") {
  const double re = 2.1;
  CHECK(KoshizukaWeight::value(1.0, re) == doctest::Approx(1.1));
  CHECK(KoshizukaWeight::value(re, re) == 0.0);
  CHECK(KoshizukaWeight::value(3.0, re) == 0.0);
  CHECK(KoshizukaWeight::value(0.0, re) == doctest::Approx(99.0));
  CHECK(KoshizukaWeight::value(1e-9, re) == doctest::Approx(99.0));
}

TEST_CASE("kernels.weight: Wendland C2 is smooth, bounded and compact") {
  const double re = 2.0;
  CHECK(WendlandC2Weight::value(0.0, re) == 1.0);
  CHECK(WendlandC2Weight::value(re, re) == 0.0);
  CHECK(WendlandC2Weight::value(1.0, re) == doctest::Approx(0.0625 * 3.0));
  // Monotone decreasing on [0, re).
  double prev = 2.0;
  for (double r = 0; r < re; r += 0.01) {
    const double w = WendlandC2Weight::value(r, re);
    CHECK(w <= prev);
    prev = w;
  }
  static_assert(check_weight<KoshizukaWeight>() && check_weight<WendlandC2Weight>());
}

}  // TEST_SUITE
