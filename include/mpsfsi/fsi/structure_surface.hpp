// SPDX-License-Identifier: BSD-3-Clause
#pragma once

// structure_normals() lives with the solid (the failure criterion samples the stress at the
// surface too); this header keeps the FSI include path.
#include "mpsfsi/solid/structure_surface.hpp"
