// SPDX-License-Identifier: BSD-3-Clause
// Must not compile: an iterative coupling scheme with a stress model that has no checkpoint state,
// through which the coupler returns the structure to the start of each step.
#include "mpsfsi/fluid/fluid_solver.hpp"
#include "mpsfsi/fsi/fsi_coupler.hpp"
#include "mpsfsi/solid/elastic_solver.hpp"

struct ModelWithoutCheckpoint : mpsfsi::CorrectedTotalLagrangian<2> {
  template <class Archive>
  void checkpoint_state(Archive&) = delete;
};
struct Policies : mpsfsi::SolidDefaults<2> {
  using stress_model = ModelWithoutCheckpoint;
};
static_assert(sizeof(mpsfsi::FsiCoupler<mpsfsi::FluidSolver<2>, mpsfsi::ElasticSolver<2, Policies>,
                                        mpsfsi::SubIterated>) > 0);
