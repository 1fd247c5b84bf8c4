// SPDX-License-Identifier: BSD-3-Clause
// A second translation unit that includes every header: a non-inline function defined in a
// header would make the unit-test executable fail to link (an ODR error caught at build time).
#include <doctest/doctest.h>

#include <string>

#include "mpsfsi/mpsfsi.hpp"

TEST_SUITE("core") {
TEST_CASE("core.odr: the umbrella header links into two translation units") {
  CHECK(std::string(mpsfsi::version_string) == MPSFSI_VERSION_STRING);
  CHECK(mpsfsi::version_major * 10000 + mpsfsi::version_minor * 100 + mpsfsi::version_patch ==
        MPSFSI_VERSION_MAJOR * 10000 + MPSFSI_VERSION_MINOR * 100 + MPSFSI_VERSION_PATCH);
}
}  // TEST_SUITE
