// SPDX-License-Identifier: BSD-3-Clause
// Must not compile: a contact model without touching().
#include "mpsfsi/solid/elastic_solver.hpp"

struct NoContactAtAll {};
struct Policies : mpsfsi::SolidDefaults<2> {
  using contact = NoContactAtAll;
};
static_assert(sizeof(mpsfsi::ElasticSolver<2, Policies>) > 0);
