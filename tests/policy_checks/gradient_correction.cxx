// SPDX-License-Identifier: BSD-3-Clause
// Must not compile: a gradient correction without update/apply/is_corrected.
#include "mpsfsi/fluid/fluid_solver.hpp"

struct NoCorrection {};
struct Policies : mpsfsi::FluidDefaults<2> {
  using gradient_correction = NoCorrection;
};
static_assert(sizeof(mpsfsi::FluidSolver<2, Policies>) > 0);
