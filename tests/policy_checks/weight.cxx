// SPDX-License-Identifier: BSD-3-Clause
// Must not compile: a weight without value(r, re). CTest expects the static_assert's message.
#include "mpsfsi/fluid/fluid_solver.hpp"

struct NoValue {};
struct Policies : mpsfsi::FluidDefaults<2> {
  using weight = NoValue;
};
static_assert(sizeof(mpsfsi::FluidSolver<2, Policies>) > 0);
