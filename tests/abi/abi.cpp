// SPDX-License-Identifier: BSD-3-Clause
// Two translation units built for different instruction sets, linked into one program
// (core/abi.hpp): each uses its own mpsfsi symbols, with its own SIMD width, and both compute the
// same motion.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>

#include "abi/abi_report.hpp"

namespace {

// Largest difference between the coordinates of two runs.
double largest_difference(const AbiReport& a, const AbiReport& b) {
  double largest = 0;
  for (std::size_t k = 0; k < a.positions.size(); ++k) largest = std::max(largest, std::abs(a.positions[k] - b.positions[k]));
  return largest;
}

}  // namespace

TEST_SUITE("abi") {

TEST_CASE("abi: units built with -mavx2 and with -mno-avx link and each runs its own solver") {
  if (!__builtin_cpu_supports("avx2") || !__builtin_cpu_supports("fma")) {
    MESSAGE("this CPU has no AVX2/FMA: the -mavx2 unit cannot run here");
    return;
  }
  const AbiReport avx = run_with_avx(), sse2 = run_with_sse2();
  CHECK(avx.lanes == 4);
  CHECK(sse2.lanes == 2);
  CHECK(avx.solver_type != sse2.solver_type);  // different symbols: nothing is merged at link time
  REQUIRE(avx.positions.size() == sse2.positions.size());
  // The same arithmetic but for fused multiply-adds in the AVX2 unit: round-off, 1e-12 of the
  // plate's 0.2 m length.
  CHECK(largest_difference(avx, sse2) < 0.2e-12);
}

#if defined(MPSFSI_ABI_TEST_AVX512)
TEST_CASE("abi: a unit built with -march=x86-64-v4 links beside them and runs 8 lanes") {
  if (!__builtin_cpu_supports("avx512f") || !__builtin_cpu_supports("avx512bw") || !__builtin_cpu_supports("avx512dq") ||
      !__builtin_cpu_supports("avx512vl")) {
    MESSAGE("this CPU has no AVX-512 F/BW/DQ/VL: the x86-64-v4 unit cannot run here");
    return;
  }
  const AbiReport avx512 = run_with_avx512(), sse2 = run_with_sse2();
  CHECK(avx512.lanes == 8);
  CHECK(avx512.solver_type != sse2.solver_type);
  REQUIRE(avx512.positions.size() == sse2.positions.size());
  CHECK(largest_difference(avx512, sse2) < 0.2e-12);  // round-off, as above
}
#endif

}  // TEST_SUITE
