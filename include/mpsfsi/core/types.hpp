// SPDX-License-Identifier: BSD-3-Clause
#pragma once

#include <Eigen/Core>
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

// The one definition of "within radius" used by every neighbour search and by the tests'
// brute-force reference, so that all of them agree to the last bit on pairs at exactly re.
template <int Dim, class Scalar>
inline Scalar squared_distance(const Vec<Dim, Scalar>& a, const Vec<Dim, Scalar>& b) {
  Scalar s = 0;
  for (int k = 0; k < Dim; ++k) {
    const Scalar d = b[k] - a[k];
    s += d * d;
  }
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
