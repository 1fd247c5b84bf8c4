// SPDX-License-Identifier: BSD-3-Clause
#pragma once

#include <Eigen/Core>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "mpsfsi/core/abi.hpp"

namespace mpsfsi {
inline namespace MPSFSI_ABI {

// Particle index. 32 bits halve the memory traffic of neighbour lists; 2^31 particles is far
// beyond what one process of this library simulates.
using Index = std::int32_t;
// Position in a CSR index array (neighbour counts summed over all particles).
using Offset = std::int64_t;

template <int Dim, class Scalar = double>
using Vec = Eigen::Matrix<Scalar, Dim, 1>;

template <int Dim, class Scalar = double>
using Mat = Eigen::Matrix<Scalar, Dim, Dim>;

// Storage for one vector per particle. Fixed-size Eigen types in std::vector are safe in C++17
// (aligned operator new), so no aligned_allocator is needed.
template <int Dim, class Scalar = double>
using VecArray = std::vector<Vec<Dim, Scalar>>;

template <int Dim, class Scalar = double>
using MatArray = std::vector<Mat<Dim, Scalar>>;

namespace detail {

template <int Dim>
inline constexpr bool is_supported_dim = (Dim == 2 || Dim == 3);

// s + d d, rounded once where the instruction set has FMA. Written out, s + d d with s itself a
// product leaves the compiler free to fuse either product, and two translation units (or two
// loops) may choose differently.
template <class Scalar>
inline Scalar add_square(Scalar s, Scalar d) {
#if defined(__FMA__)
  return std::fma(d, d, s);
#else
  return s + d * d;
#endif
}

// The one definition of "within radius" used by every neighbour search and by the tests'
// brute-force reference, so that all of them agree to the last bit on pairs at exactly re:
// d0 d0, then the other axes' squares added in order by add_square (detail::append_within
// forms it the same way, also eight at a time).
template <int Dim, class Scalar>
inline Scalar squared_distance(const Vec<Dim, Scalar>& a, const Vec<Dim, Scalar>& b) {
  const Scalar d0 = b[0] - a[0];
  Scalar s = d0 * d0;
  for (int k = 1; k < Dim; ++k) s = add_square(s, b[k] - a[k]);
  return s;
}

// Index of the first entry with a NaN or infinite component, or values.size() if there is none.
template <int Dim, class Scalar>
std::size_t first_non_finite(const VecArray<Dim, Scalar>& values) {
  for (std::size_t i = 0; i < values.size(); ++i)
    if (!values[i].allFinite()) return i;
  return values.size();
}

}  // namespace detail
}  // namespace MPSFSI_ABI
}  // namespace mpsfsi
