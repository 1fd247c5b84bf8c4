// SPDX-License-Identifier: BSD-3-Clause
// Must not compile: a stress model without stresses().
#include "mpsfsi/solid/elastic_solver.hpp"

struct NoStresses : mpsfsi::CorrectedTotalLagrangian<2> {
  void stresses() = delete;
};
struct Policies : mpsfsi::SolidDefaults<2> {
  using stress_model = NoStresses;
};
static_assert(sizeof(mpsfsi::ElasticSolver<2, Policies>) > 0);
