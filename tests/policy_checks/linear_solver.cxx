// SPDX-License-Identifier: BSD-3-Clause
// Must not compile: a linear solver whose solve() has the wrong arguments.
#include "mpsfsi/fluid/fluid_solver.hpp"

struct WrongSolve {
  mpsfsi::SolveReport solve(const mpsfsi::PpeMatrix&, mpsfsi::PpeVector&) { return {}; }
};
struct Policies : mpsfsi::FluidDefaults<2> {
  using linear_solver = WrongSolve;
};
static_assert(sizeof(mpsfsi::FluidSolver<2, Policies>) > 0);
