// SPDX-License-Identifier: BSD-3-Clause
#pragma once

#include <cstddef>
#include <cstdint>
#include <type_traits>

#if defined(__AVX512F__) && defined(__AVX512VL__)
#include <immintrin.h>
#endif

#include "mpsfsi/core/abi.hpp"
#include "mpsfsi/core/detail/csr_builder.hpp"
#include "mpsfsi/core/types.hpp"

namespace mpsfsi {
inline namespace MPSFSI_ABI {
namespace detail {

// Appends to `sink` every point k in [begin, end) of a cell list's run (its coordinates in cell
// order, one array per axis: s[0], s[1], s[Dim - 1]) that lies within sqrt(r2) of x and is not
// `self`: its source index order[k] and its squared distance. The caller reserves end - begin
// slots plus candidate_run_slack.
//
// The squared distance is formed as detail::squared_distance forms it (with FMA:
// fma(dz, dz, fma(dy, dy, dx dx))), so a pair at the radius is taken or left alike by every
// search and by the tests' brute-force reference.
//
// With AVX-512 (F and VL) eight candidates at a time: their distances side by side, and the
// accepted ones packed to the front of a register (compress) and stored whole; the sink's slack
// takes the unused rest. Written one at a time, with the count advanced by the test (a cell
// list accepts about one candidate in three in 2D and one in eight in 3D, too often for a
// branch), each candidate costs a store, a compare and a dependent add (docs/performance.md,
// neighbour search).
inline constexpr std::size_t candidate_run_slack = 8;

template <int Dim, class Scalar>
void append_within(const Scalar* const* s, const Index* order, Index begin, Index end, const Vec<Dim, Scalar>& x,
                   Scalar r2, Index self, CsrSink<Scalar>& sink) {
  const Scalar* const sx = s[0];
  const Scalar* const sy = s[1];
  const Scalar* const sz = s[Dim - 1];
  Index k = begin;
#if defined(__AVX512F__) && defined(__AVX512VL__)
  if constexpr (std::is_same_v<Scalar, double> && std::is_same_v<Index, std::int32_t>) {
    const __m512d x0 = _mm512_set1_pd(x[0]), y0 = _mm512_set1_pd(x[1]), z0 = _mm512_set1_pd(x[Dim - 1]);
    const __m512d radius2 = _mm512_set1_pd(r2);
    const __m256i self8 = _mm256_set1_epi32(self);
    Index* const indices = sink.index_slots();
    double* const squared = sink.squared_slots();
    std::size_t count = 0;
    for (; k + 8 <= end; k += 8) {
      const __m512d dx = _mm512_sub_pd(_mm512_loadu_pd(sx + k), x0);
      const __m512d dy = _mm512_sub_pd(_mm512_loadu_pd(sy + k), y0);
      __m512d d2 = _mm512_fmadd_pd(dy, dy, _mm512_mul_pd(dx, dx));
      if constexpr (Dim == 3) {
        const __m512d dz = _mm512_sub_pd(_mm512_loadu_pd(sz + k), z0);
        d2 = _mm512_fmadd_pd(dz, dz, d2);
      }
      const __m256i j = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(order + k));
      const __mmask8 accept = _mm512_cmp_pd_mask(d2, radius2, _CMP_LE_OQ) & _mm256_cmpneq_epi32_mask(j, self8);
      _mm256_storeu_si256(reinterpret_cast<__m256i*>(indices + count), _mm256_maskz_compress_epi32(accept, j));
      if (squared) _mm512_storeu_pd(squared + count, _mm512_maskz_compress_pd(accept, d2));
      count += static_cast<std::size_t>(__builtin_popcount(accept));
    }
    sink.advance(count);
  }
#endif
  for (; k < end; ++k) {
    const Scalar dx = sx[k] - x[0];
    Scalar d2 = add_square(dx * dx, sy[k] - x[1]);
    if constexpr (Dim == 3) d2 = add_square(d2, sz[k] - x[Dim - 1]);
    const Index j = order[k];
    sink.put(j, d2, (d2 <= r2) & (j != self));
  }
}

}  // namespace detail
}  // namespace MPSFSI_ABI
}  // namespace mpsfsi
