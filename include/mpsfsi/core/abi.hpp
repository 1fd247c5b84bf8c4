// SPDX-License-Identifier: BSD-3-Clause
#pragma once

// Every mpsfsi declaration lives in an inline namespace named after the instruction set the
// translation unit is compiled for, because data layouts depend on it (the solid's force loop
// packs its particles in groups sized by the SIMD width: CorrectedTotalLagrangian::lanes). Without it, two
// translation units of one program built with different -m flags would define two different
// classes under one name (an ODR violation that links and misbehaves). With it they use different
// symbols: each works on its own, and passing a solver from one to the other fails to link.
// User code names the types as mpsfsi::X; the inline namespace is invisible there.
#if defined(__AVX512F__)
#define MPSFSI_ABI abi_avx512
#elif defined(__AVX__)
#define MPSFSI_ABI abi_avx
#else
#define MPSFSI_ABI abi_sse2
#endif

namespace mpsfsi {
inline namespace MPSFSI_ABI {
// Doubles per SIMD register of the instruction set above.
#if defined(__AVX512F__)
inline constexpr int simd_double_lanes = 8;
#elif defined(__AVX__)
inline constexpr int simd_double_lanes = 4;
#else
inline constexpr int simd_double_lanes = 2;
#endif
}  // namespace MPSFSI_ABI
}  // namespace mpsfsi
