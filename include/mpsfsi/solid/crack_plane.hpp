// SPDX-License-Identifier: BSD-3-Clause
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

#include "mpsfsi/core/abi.hpp"
#include "mpsfsi/core/types.hpp"
#include "mpsfsi/solid/bonds.hpp"

namespace mpsfsi {
inline namespace MPSFSI_ABI {

// Bond cutting across the crack plane of a failing particle (eqs 34-35, read as docs/theory.md,
// section 5.3 explains: with r_c the midpoint of the bond, as printed, the two ends of every bond
// lie on opposite sides of a plane through it, so eq 34 cannot tell which bonds the crack crosses).
// The rule implemented: the crack plane goes through the failing particle c (r_c = x_c) with
// normal n_c. An intact bond (i, j) is cut when
//   (eq 34)  i and j lie on different sides, with `slab_half_width` b = 0:
//              side(p) = [(x_p - x_c) . n_c >= 0]
//            (a particle on the plane, c itself included, counts on the + side, so c keeps the
//            bonds on its + side and loses those to the - side: the sign of n_c matters;
//            SolidParameters::crack_side says how a failing particle's is chosen); with b > 0
//            the plane is a slab, and a particle lies below it, in it or above it:
//              side(p) = -1, 0, +1 as (x_p - x_c) . n_c <= -b, < b, >= b
//            (CrackSide::slab, b = l0/2: c and its slab lose the bonds across both faces, and
//            the sign of n_c does not matter), and
//   (eq 35)  at least one of them is within Cw l0 of c measured along the plane,
//            |(x_p - x_c) - ((x_p - x_c) . n_c) n_c| <= Cw l0,  Cw = sqrt(d)/2 by default.
// The crack thus opens one particle wide around c and grows as its neighbours fail in turn.
// Candidates are c and the particles two bonds away at most (cut or not) within
// sqrt(re^2 + (Cw l0)^2) of c: every cut bond has an end there. Returns the number of bonds cut;
// the particles whose bonds changed are appended to `touched`.
template <int Dim, class Scalar>
std::size_t cut_bonds_across_plane(BondList<Dim, Scalar>& bonds, const VecArray<Dim, Scalar>& x, std::size_t c,
                                   const Vec<Dim, Scalar>& normal, Scalar half_width, Scalar re,
                                   std::vector<std::size_t>& touched, std::vector<std::size_t>& scratch,
                                   Scalar slab_half_width = 0) {
  const Vec<Dim, Scalar> xc = x[c];
  auto offset = [&](std::size_t p) { return Vec<Dim, Scalar>(x[p] - xc); };
  auto side = [&](std::size_t p) {
    const Scalar d = offset(p).dot(normal);
    if (slab_half_width > 0) return d >= slab_half_width ? 1 : (d <= -slab_half_width ? -1 : 0);
    return d >= 0 ? 1 : -1;
  };
  auto along_plane = [&](std::size_t p) {
    const Vec<Dim, Scalar> d = offset(p);
    return (d - d.dot(normal) * normal).norm();
  };
  const Scalar reach2 = re * re + half_width * half_width;
  // Candidate set: the 2-ring of c in the bond graph, within reach.
  scratch.clear();
  scratch.push_back(c);
  for (Offset b = bonds.begin(c); b < bonds.end(c); ++b) {
    const auto j = static_cast<std::size_t>(bonds.neighbor(b));
    scratch.push_back(j);
    for (Offset e = bonds.begin(j); e < bonds.end(j); ++e) scratch.push_back(static_cast<std::size_t>(bonds.neighbor(e)));
  }
  std::sort(scratch.begin(), scratch.end());
  scratch.erase(std::unique(scratch.begin(), scratch.end()), scratch.end());
  std::size_t cut = 0;
  for (const std::size_t i : scratch) {
    if (offset(i).squaredNorm() > reach2 || along_plane(i) > half_width) continue;
    const int side_i = side(i);
    for (Offset b = bonds.begin(i); b < bonds.end(i); ++b) {
      const auto j = static_cast<std::size_t>(bonds.neighbor(b));
      if (!bonds.intact(b) || side(j) == side_i) continue;
      bonds.cut(b);
      touched.push_back(i);
      touched.push_back(j);
      ++cut;
    }
  }
  return cut;
}

// The side of its own crack plane that a failing particle c stays on with CrackSide::attachment.
// A principal direction has no sign, yet cut_bonds_across_plane keeps c with the bonds on the +
// side of the normal it is given; a fixed sign convention (n_x >= 0) sends c to the left-hand side
// of one crack and to the right-hand side of its mirror image, and a mirror-symmetric specimen
// cracks asymmetrically. Here c stays with the side that holds it more firmly across the plane:
// the normal is turned so that the attachment
//   A = sum over intact bonds of w_cj (x_j - x_c) . n / |x_j - x_c|
// (each bond's weight times the cosine of its angle to n, current positions) is not negative.
// A is continuous in n, so a neighbour close to the plane counts little on either side. A cut
// bond removes its share; in an undamaged neighbourhood A is zero up to the deformation, which
// then decides. Where A is zero to round-off (a lattice at rest, a particle on a mirror plane) the
// normal keeps the sign it came with. A changes sign with a mirror image of the solid, so the
// crack pattern is mirrored too (docs/theory.md, section 5.3).
template <int Dim, class Scalar>
Vec<Dim, Scalar> orient_toward_attachment(const BondList<Dim, Scalar>& bonds, const VecArray<Dim, Scalar>& x,
                                          std::size_t c, const Vec<Dim, Scalar>& normal) {
  Scalar attachment = 0, total = 0;
  for (Offset b = bonds.begin(c); b < bonds.end(c); ++b) {
    if (!bonds.intact(b)) continue;
    const Scalar w = bonds.weight(b);
    const Vec<Dim, Scalar> d = x[static_cast<std::size_t>(bonds.neighbor(b))] - x[c];
    attachment += w * d.dot(normal) / d.norm();
    total += w;
  }
  // Sums over a mirrored neighbourhood agree to round-off whatever their order of summation:
  // within a few hundred ulps of the total weight, A is a tie.
  const Scalar tie = Scalar(256) * std::numeric_limits<Scalar>::epsilon() * total;
  return attachment < -tie ? Vec<Dim, Scalar>(-normal) : normal;
}

}  // namespace MPSFSI_ABI
}  // namespace mpsfsi
