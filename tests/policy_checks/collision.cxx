// SPDX-License-Identifier: BSD-3-Clause
// Must not compile: a collision model without apply().
#include "mpsfsi/fluid/fluid_solver.hpp"

struct NoApply {};
struct Policies : mpsfsi::FluidDefaults<2> {
  using collision = NoApply;
};
static_assert(sizeof(mpsfsi::FluidSolver<2, Policies>) > 0);
