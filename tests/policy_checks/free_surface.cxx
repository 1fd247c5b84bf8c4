// SPDX-License-Identifier: BSD-3-Clause
// Must not compile: a free-surface detector without detect().
#include "mpsfsi/fluid/fluid_solver.hpp"

struct NoDetect {};
struct Policies : mpsfsi::FluidDefaults<2> {
  using free_surface = NoDetect;
};
static_assert(sizeof(mpsfsi::FluidSolver<2, Policies>) > 0);
