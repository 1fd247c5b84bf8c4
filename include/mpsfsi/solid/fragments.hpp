// SPDX-License-Identifier: BSD-3-Clause
#pragma once

#include <cstddef>
#include <vector>

#include "mpsfsi/core/abi.hpp"
#include "mpsfsi/core/types.hpp"
#include "mpsfsi/solid/bonds.hpp"

namespace mpsfsi {
inline namespace MPSFSI_ABI {

// The fragments of a fractured solid: the connected pieces of its intact-bond graph. Two
// particles are in the same fragment when a path of intact bonds joins them; a solid is broken
// in two exactly when its particles fall into two fragments. Bodies never share bonds, so each
// unbroken body (a beam, a support) is one fragment.
struct Fragments {
  std::vector<Index> label;        // fragment of each particle, 0, 1, ... in order of first particle
  std::vector<std::size_t> sizes;  // particles in each fragment

  std::size_t count() const { return sizes.size(); }
  // Number of fragments with more than min_size particles (a broken beam has two such; loose
  // particles and chips at the crack faces are left out).
  std::size_t count_larger_than(std::size_t min_size) const {
    std::size_t n = 0;
    for (const auto s : sizes) n += s > min_size ? 1 : 0;
    return n;
  }
};

// Labels the fragments of `bonds` by depth-first search over intact bonds, O(particles + bonds).
// `keep(i, b)` may leave intact bonds out (e.g. overstretched ones, for a diagnostic). It is
// asked only for intact bonds whose far end is not yet labelled, so it must be symmetric:
// keep(i, b) == keep(j, reverse(b)).
template <int Dim, class Scalar, class KeepBond>
Fragments find_fragments(const BondList<Dim, Scalar>& bonds, KeepBond keep) {
  const std::size_t n = bonds.num_particles();
  Fragments f;
  f.label.assign(n, Index(-1));
  std::vector<std::size_t> stack;
  for (std::size_t start = 0; start < n; ++start) {
    if (f.label[start] >= 0) continue;
    const auto id = static_cast<Index>(f.sizes.size());
    f.sizes.push_back(0);
    f.label[start] = id;
    stack.assign(1, start);
    while (!stack.empty()) {
      const std::size_t i = stack.back();
      stack.pop_back();
      ++f.sizes.back();
      for (Offset b = bonds.begin(i); b < bonds.end(i); ++b) {
        const auto j = static_cast<std::size_t>(bonds.neighbor(b));
        if (f.label[j] >= 0 || !bonds.intact(b) || !keep(i, b)) continue;
        f.label[j] = id;
        stack.push_back(j);
      }
    }
  }
  return f;
}

template <int Dim, class Scalar>
Fragments find_fragments(const BondList<Dim, Scalar>& bonds) {
  return find_fragments(bonds, [](std::size_t, Offset) { return true; });
}

}  // namespace MPSFSI_ABI
}  // namespace mpsfsi
