// SPDX-License-Identifier: BSD-3-Clause
// Must NOT compile: FsiCoupler refuses a 2D fluid with a 3D solid at compile time, with a message
// that says so (CTest unit.fsi_dimension_mismatch builds this and looks for the message).
#include "mpsfsi/fluid/fluid_solver.hpp"
#include "mpsfsi/fsi/fsi_coupler.hpp"
#include "mpsfsi/solid/elastic_solver.hpp"

using Mismatched = mpsfsi::FsiCoupler<mpsfsi::FluidSolver<2>, mpsfsi::ElasticSolver<3>>;
constexpr int dimension = Mismatched::dimension;
