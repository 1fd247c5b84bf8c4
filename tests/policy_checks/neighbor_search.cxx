// SPDX-License-Identifier: BSD-3-Clause
// Must not compile: a neighbour search without self_query().
#include "mpsfsi/fluid/fluid_solver.hpp"

struct BuildOnly {
  static constexpr int dim = 2;
  using scalar_type = double;
  explicit BuildOnly(double) {}
  void build(const mpsfsi::VecArray<2>&) {}
};
struct Policies : mpsfsi::FluidDefaults<2> {
  using neighbor_search = BuildOnly;
};
static_assert(sizeof(mpsfsi::FluidSolver<2, Policies>) > 0);
