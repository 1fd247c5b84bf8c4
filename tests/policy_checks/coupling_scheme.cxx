// SPDX-License-Identifier: BSD-3-Clause
// Must not compile: an iterative coupling scheme without its iteration controls.
#include "mpsfsi/fluid/fluid_solver.hpp"
#include "mpsfsi/fsi/fsi_coupler.hpp"
#include "mpsfsi/solid/elastic_solver.hpp"

struct IterativeWithoutControls {
  static constexpr bool iterative = true;
  static constexpr const char* name = "incomplete";
};
static_assert(sizeof(mpsfsi::FsiCoupler<mpsfsi::FluidSolver<2>, mpsfsi::ElasticSolver<2>, IterativeWithoutControls>) > 0);
