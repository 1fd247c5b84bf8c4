// SPDX-License-Identifier: BSD-3-Clause
// Must not compile: a failure model without principal().
#include "mpsfsi/fracture/fracture_process.hpp"
#include "mpsfsi/solid/elastic_solver.hpp"

struct EnabledOnly {
  static constexpr bool enabled = true;
};
struct Policies : mpsfsi::SolidDefaults<2> {
  using failure = EnabledOnly;
};
static_assert(sizeof(mpsfsi::ElasticSolver<2, Policies>) > 0);
