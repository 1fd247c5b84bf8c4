// SPDX-License-Identifier: BSD-3-Clause
// Must not compile: a coupling scheme with settings but no advance() to run a step with them.
#include "mpsfsi/fluid/fluid_solver.hpp"
#include "mpsfsi/fsi/fsi_coupler.hpp"
#include "mpsfsi/solid/elastic_solver.hpp"

struct SchemeWithoutAdvance {
  static constexpr bool iterative = true;
  static constexpr const char* name = "incomplete";
  int max_iterations = 10;
  double tolerance = 1e-3;
};
static_assert(sizeof(mpsfsi::FsiCoupler<mpsfsi::FluidSolver<2>, mpsfsi::ElasticSolver<2>, SchemeWithoutAdvance>) > 0);
