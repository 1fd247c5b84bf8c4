// SPDX-License-Identifier: BSD-3-Clause
#pragma once

// OpenMP behind macros, so that a consumer building without -fopenmp gets serial code and no
// unknown-pragma warnings.
#if defined(_OPENMP)
#include <omp.h>

#include "mpsfsi/core/abi.hpp"
#define MPSFSI_PRAGMA(x) _Pragma(#x)
#define MPSFSI_OMP(x) MPSFSI_PRAGMA(omp x)
#else
#define MPSFSI_OMP(x)
#endif

namespace mpsfsi {
inline namespace MPSFSI_ABI {
namespace parallel {

// Threads an OpenMP parallel region will use (1 without OpenMP).
inline int max_threads() {
#if defined(_OPENMP)
  return omp_get_max_threads();
#else
  return 1;
#endif
}

// Id of the calling thread inside a parallel region (0 outside or without OpenMP).
inline int thread_id() {
#if defined(_OPENMP)
  return omp_get_thread_num();
#else
  return 0;
#endif
}

// Threads in the current team (1 outside a parallel region or without OpenMP).
inline int team_size() {
#if defined(_OPENMP)
  return omp_get_num_threads();
#else
  return 1;
#endif
}

// Sets the thread count for later parallel regions; no effect without OpenMP.
inline void set_num_threads(int n) {
#if defined(_OPENMP)
  omp_set_num_threads(n > 0 ? n : 1);
#else
  (void)n;
#endif
}

}  // namespace parallel
}  // namespace MPSFSI_ABI
}  // namespace mpsfsi
