// SPDX-License-Identifier: BSD-3-Clause
// A second translation unit that includes every header: a non-inline function defined in a
// header would make the unit-test executable fail to link (an ODR error caught at build time).
#include <doctest/doctest.h>

#include "mpsfsi/mpsfsi.hpp"

TEST_CASE("core.odr: the umbrella header links into two translation units") {
  CHECK(std::string(mpsfsi::version_string) == MPSFSI_VERSION_STRING);
}
