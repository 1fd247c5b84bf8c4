// SPDX-License-Identifier: BSD-3-Clause
#pragma once

#include <algorithm>

#include "mpsfsi/core/abi.hpp"

namespace mpsfsi {
inline namespace MPSFSI_ABI {

// Coulomb friction of a penalty contact (docs/theory.md, section 3.5), shared by PenaltyContact
// (particle pairs) and RigidObstacle (particle and body). r is the contact's relative position,
// e its unit normal, `normal` the normal force (taken as 0 if negative), mu the coefficient and
// k the tangential stiffness; `anchor` is where r was when the contact began. The tangential
// stretch s of r - anchor is capped at mu f_n / k (the anchor then follows: sliding), written to
// `stretch`, and the force -k s returned.
template <class Vec, class Scalar>
Vec coulomb_friction(const Vec& r, const Vec& e, Scalar normal, Scalar mu, Scalar k, Vec& anchor, Vec& stretch) {
  const Vec offset = r - anchor;
  stretch = offset - offset.dot(e) * e;
  const Scalar cap = mu * std::max(normal, Scalar(0));
  const Scalar spring = k * stretch.norm();
  if (spring > cap) {
    stretch *= cap / spring;
    anchor = r - stretch;
  }
  return -k * stretch;
}

}  // namespace MPSFSI_ABI
}  // namespace mpsfsi
