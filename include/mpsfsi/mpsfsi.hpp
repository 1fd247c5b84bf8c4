// SPDX-License-Identifier: BSD-3-Clause
#pragma once

// Umbrella header: everything public in mpsfsi.
#include "mpsfsi/version.hpp"

#include "mpsfsi/core/cell_list_search.hpp"
#include "mpsfsi/core/error.hpp"
#include "mpsfsi/core/kd_tree_search.hpp"
#include "mpsfsi/core/neighbor_list.hpp"
#include "mpsfsi/core/neighbor_search.hpp"
#include "mpsfsi/core/parallel.hpp"
#include "mpsfsi/core/particle_set.hpp"
#include "mpsfsi/core/types.hpp"

#include "mpsfsi/kernels/divergence.hpp"
#include "mpsfsi/kernels/gradient.hpp"
#include "mpsfsi/kernels/gradient_correction.hpp"
#include "mpsfsi/kernels/laplacian.hpp"
#include "mpsfsi/kernels/lattice_constants.hpp"
#include "mpsfsi/kernels/number_density.hpp"
#include "mpsfsi/kernels/weight.hpp"

#include "mpsfsi/fluid/collision.hpp"
#include "mpsfsi/fluid/fluid_parameters.hpp"
#include "mpsfsi/fluid/fluid_solver.hpp"
#include "mpsfsi/fluid/free_surface.hpp"
#include "mpsfsi/fluid/linear_solver.hpp"
#include "mpsfsi/fluid/ppe.hpp"
// mpsfsi/fluid/hypre_amg.hpp is left out: it needs hypre and MPI (target mpsfsi::hypre).

#include "mpsfsi/solid/bonds.hpp"
#include "mpsfsi/solid/contact.hpp"
#include "mpsfsi/solid/corrected_total_lagrangian.hpp"
#include "mpsfsi/solid/deformation.hpp"
#include "mpsfsi/solid/elastic_solver.hpp"
#include "mpsfsi/solid/hwang_model.hpp"
#include "mpsfsi/solid/solid_parameters.hpp"
#include "mpsfsi/fracture/crack_plane.hpp"
#include "mpsfsi/fracture/failure_criteria.hpp"
#include "mpsfsi/io/csv_writer.hpp"
#include "mpsfsi/io/progress.hpp"
#include "mpsfsi/io/pvd_writer.hpp"
#include "mpsfsi/io/vtu_writer.hpp"

#include "mpsfsi/core/filter_neighbors.hpp"
#include "mpsfsi/scenes/dam_break.hpp"
#include "mpsfsi/scenes/lattice.hpp"
#include "mpsfsi/scenes/oscillating_plate.hpp"
#include "mpsfsi/scenes/solid_block.hpp"
#include "mpsfsi/scenes/tank.hpp"
