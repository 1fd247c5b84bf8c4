// SPDX-License-Identifier: BSD-3-Clause
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <random>

#include "mpsfsi/fracture/failure_criteria.hpp"
#include "mpsfsi/fracture/failure_stress.hpp"
#include "mpsfsi/kernels/weight.hpp"
#include "mpsfsi/scenes/solid_block.hpp"
#include "mpsfsi/solid/deformation.hpp"

using namespace mpsfsi;

TEST_SUITE("fracture") {

// A full neighbourhood's weight: the largest sum of bond weights over the particles (n0).
template <int Dim>
double full_neighbourhood_weight(const BondList<Dim>& bonds, std::size_t n) {
  double n0 = 0;
  for (std::size_t p = 0; p < n; ++p) {
    double sum = 0;
    for (Offset b = bonds.begin(p); b < bonds.end(p); ++b) sum += bonds.weight(b);
    n0 = std::max(n0, sum);
  }
  return n0;
}

// A bar of particles at spacing l0 from the origin to `upper`, bonded within re, and the heights
// of its bottom and top rows.
template <int Dim>
struct BondedBar {
  BondedBar(const Vec<Dim>& upper, double l0, double re)
      : reference(scenes::material_block<Dim>(Vec<Dim>::Zero(), upper, l0).positions()) {
    bonds.template build<KoshizukaWeight>(reference, std::vector<std::int32_t>(reference.size(), 0), re);
    lowest = highest = reference[0][1];
    for (const auto& p : reference) lowest = std::min(lowest, p[1]), highest = std::max(highest, p[1]);
  }
  VecArray<Dim, double> reference;
  BondList<Dim> bonds;
  double lowest = 0, highest = 0;
};

// The averaged failure stress (no surface read-out here, so every particle averages over all its
// bonds). One particle i in the middle of a block carries a stress, the others none, so the
// average at i is its own share: w_self / (w_self + sum of its intact weights). Bonds cut after
// the first read give their weight to i's own stress; bonds already cut at the first read (an
// imposed notch) are absent, as in the average before.
TEST_CASE_TEMPLATE("fracture.failure_stress: a particle's cut bonds weigh its own stress, notches do not", T,
                   std::integral_constant<int, 2>, std::integral_constant<int, 3>) {
  constexpr int Dim = T::value;
  const double l0 = 0.01, re = 2.1 * l0;
  const auto block = scenes::material_block<Dim>(Vec<Dim>::Zero(), Vec<Dim>::Constant(0.07), l0);
  const auto& x = block.positions();
  const std::vector<std::int32_t> body(x.size(), 0);
  std::size_t i = 0;  // the particle nearest the centre
  for (std::size_t k = 0; k < x.size(); ++k)
    if ((x[k] - Vec<Dim>::Constant(0.035)).norm() < (x[i] - Vec<Dim>::Constant(0.035)).norm()) i = k;
  MatArray<Dim, double> point(x.size(), Mat<Dim>::Zero());
  point[i](0, 0) = 1e6;

  typename FailureStressReadout<Dim>::Settings settings;
  settings.l0 = l0;
  settings.self_weight = KoshizukaWeight::value(l0, re);
  const auto unloaded = [](std::size_t) { return false; };
  const auto read_at_i = [&](FailureStressReadout<Dim>& readout, const BondList<Dim>& bonds) {
    return readout.read(point, x, x, bonds, nullptr, unloaded, settings)[i](0, 0);
  };

  BondList<Dim> bonds;
  bonds.template build<KoshizukaWeight>(x, body, re);
  double all = 0;  // sum of i's bond weights
  for (Offset b = bonds.begin(i); b < bonds.end(i); ++b) all += bonds.weight(b);
  const double self = settings.self_weight;

  FailureStressReadout<Dim> readout;
  CHECK(read_at_i(readout, bonds) == doctest::Approx(1e6 * self / (self + all)).epsilon(1e-12));
  // Cut all of i's bonds but the first in its row (weight w_left).
  const double w_left = bonds.weight(bonds.begin(i));
  for (Offset b = bonds.begin(i) + 1; b < bonds.end(i); ++b) bonds.cut(b);
  // Cut since the first read: their weight goes to i's own stress, the sum of weights is kept.
  CHECK(read_at_i(readout, bonds) == doctest::Approx(1e6 * (self + all - w_left) / (self + all)).epsilon(1e-12));
  // A readout that first sees them cut treats them as a notch: i averages over what is left.
  FailureStressReadout<Dim> fresh;
  CHECK(read_at_i(fresh, bonds) == doctest::Approx(1e6 * self / (self + w_left)).epsilon(1e-12));
}

// A neighbour cut out of the solid (failed with CrackSide::slab) leaves the average as a cut bond
// does: its weight goes to the reading particle's own stress, so neither its stress nor its
// relaxed state lowers or raises the read. Particle i carries a stress and its neighbour k
// another; after k is cut out, i reads its own stress with k's weight added to its own.
TEST_CASE_TEMPLATE("fracture.failure_stress: a cut-out neighbour weighs the particle's own stress", T,
                   std::integral_constant<int, 2>, std::integral_constant<int, 3>) {
  constexpr int Dim = T::value;
  const double l0 = 0.01, re = 2.1 * l0;
  const auto block = scenes::material_block<Dim>(Vec<Dim>::Zero(), Vec<Dim>::Constant(0.07), l0);
  const auto& x = block.positions();
  std::size_t i = 0;
  for (std::size_t p = 0; p < x.size(); ++p)
    if ((x[p] - Vec<Dim>::Constant(0.035)).norm() < (x[i] - Vec<Dim>::Constant(0.035)).norm()) i = p;
  BondList<Dim> bonds;
  bonds.template build<KoshizukaWeight>(x, std::vector<std::int32_t>(x.size(), 0), re);
  const auto k = static_cast<std::size_t>(bonds.neighbor(bonds.begin(i)));
  const double w_k = bonds.weight(bonds.begin(i));
  double all = 0;
  for (Offset b = bonds.begin(i); b < bonds.end(i); ++b) all += bonds.weight(b);

  typename FailureStressReadout<Dim>::Settings settings;
  settings.l0 = l0;
  settings.self_weight = KoshizukaWeight::value(l0, re);
  const double self = settings.self_weight;
  MatArray<Dim, double> point(x.size(), Mat<Dim>::Zero());
  point[i](0, 0) = 1e6;
  point[k](0, 0) = 3e6;
  const auto unloaded = [](std::size_t) { return false; };
  FailureStressReadout<Dim> readout;
  const auto read_at_i = [&] { return readout.read(point, x, x, bonds, nullptr, unloaded, settings)[i](0, 0); };
  CHECK(read_at_i() == doctest::Approx((1e6 * self + 3e6 * w_k) / (self + all)).epsilon(1e-12));
  readout.mark_cut_out(k, x.size(), Vec<Dim>::UnitX());
  CHECK(read_at_i() == doctest::Approx(1e6 * (self + w_k) / (self + all)).epsilon(1e-12));
}

// A surface particle reads the fitted field at the outer end of its cell, X + (l0/2) n, or where
// the caller's inner_end(outer, inner) says so at the inner end, X - (l0/2) n. A bar bent by
// u_x = -k X (Y - Y_mid) (quadratic: the fit reproduces it) has its top face in compression, less
// at the inner end, and its bottom face in tension, more at the outer end: choosing the larger
// sigma_1 reads the top face's inner end and the bottom face's outer end; by default both read
// their outer ends. Each read is the SVK stress of the exact gradient at that point. A top
// particle beside a loaded or a cut-out particle of its face reads its outer end.
TEST_CASE_TEMPLATE("fracture.failure_stress: a surface particle reads the end of its cell its caller chooses", T,
                   std::integral_constant<int, 2>, std::integral_constant<int, 3>) {
  constexpr int Dim = T::value;
  const double l0 = 0.01, re = 2.1 * l0, k = 0.03;
  Vec<Dim> upper = Vec<Dim>::Constant(0.06);
  upper[0] = 0.2;
  const BondedBar<Dim> bar(upper, l0, re);
  const auto& reference = bar.reference;
  const auto& bonds = bar.bonds;
  const std::size_t n = reference.size();
  const double lowest = bar.lowest, highest = bar.highest, middle = 0.5 * (lowest + highest);
  VecArray<Dim, double> x = reference;
  for (auto& p : x) p[0] -= k * p[0] * (p[1] - middle);
  const auto gradient = [&](const Vec<Dim>& at) {
    Mat<Dim> f = Mat<Dim>::Identity();
    f(0, 0) -= k * (at[1] - middle);
    f(0, 1) -= k * at[0];
    return f;
  };
  DeformationFit<Dim, double> fit;
  fit.build(bonds, l0);
  typename FailureStressReadout<Dim>::Settings settings;
  settings.l0 = l0;
  settings.lame = {6e8, 4e8};
  settings.average = false;
  settings.n0 = full_neighbourhood_weight(bonds, n);
  const MatArray<Dim, double> point(n, Mat<Dim>::Zero());
  const auto unloaded = [](std::size_t) { return false; };
  const auto sigma_1 = [](const Mat<Dim>& t) {
    Vec<Dim> direction;
    return MaxPrincipalStress::principal<Dim, double>(t, direction);
  };
  const auto larger = [&](const Mat<Dim>& outer, const Mat<Dim>& inner) { return sigma_1(inner) > sigma_1(outer); };
  FailureStressReadout<Dim> by_default, chosen;
  const MatArray<Dim, double> outer_read = by_default.read(point, x, reference, bonds, &fit, unloaded, settings);
  const MatArray<Dim, double> chosen_read = chosen.read(point, x, reference, bonds, &fit, unloaded, settings, larger);

  std::size_t top = 0, bottom = 0;
  for (std::size_t p = 0; p < n; ++p) {
    const Vec<Dim>& at = reference[p];
    bool inside_edges = at[0] > 0.06 && at[0] < 0.14;  // away from the end faces and, in 3D, the side faces
    for (int d = 2; d < Dim; ++d) inside_edges = inside_edges && at[d] > 0.015 && at[d] < 0.045;
    const bool on_top = at[1] == highest, on_bottom = at[1] == lowest;
    if (!inside_edges || !(on_top || on_bottom)) continue;
    CAPTURE(p);
    Vec<Dim> half_cell = Vec<Dim>::Zero();
    half_cell[1] = on_top ? 0.5 * l0 : -0.5 * l0;
    const Mat<Dim> outer = detail::cauchy_from_svk(gradient(at + half_cell), settings.lame);
    const Mat<Dim> inner = detail::cauchy_from_svk(gradient(at - half_cell), settings.lame);
    REQUIRE((sigma_1(inner) > sigma_1(outer)) == on_top);
    const double scale = outer.norm();
    CHECK((outer_read[p] - outer).norm() < 1e-6 * scale);
    CHECK((chosen_read[p] - (on_top ? inner : outer)).norm() < 1e-6 * scale);
    (on_top ? top : bottom) += 1;
  }
  CHECK(top > 0);
  CHECK(bottom > 0);

  // Averaged, each end's samples are averaged along the face and the end is chosen on the two
  // averages: the read is, to the bit, the read of every particle at its outer end or that at its
  // inner end (where its face is whole), whichever has the larger sigma_1.
  {
    typename FailureStressReadout<Dim>::Settings averaging = settings;
    averaging.average = true;
    averaging.self_weight = KoshizukaWeight::value(l0, re);
    const auto always_inner = [](const Mat<Dim>&, const Mat<Dim>&) { return true; };
    FailureStressReadout<Dim> outer_reader, inner_reader, chosen_reader;
    const MatArray<Dim, double> outer_average =
        outer_reader.read(point, x, reference, bonds, &fit, unloaded, averaging);
    const MatArray<Dim, double> inner_average =
        inner_reader.read(point, x, reference, bonds, &fit, unloaded, averaging, always_inner);
    const auto& chosen_average = chosen_reader.read(point, x, reference, bonds, &fit, unloaded, averaging, larger);
    std::size_t differ = 0, inner_read = 0;
    for (std::size_t p = 0; p < n; ++p) {
      const bool inner = sigma_1(inner_average[p]) > sigma_1(outer_average[p]);
      const Mat<Dim>& expected = inner ? inner_average[p] : outer_average[p];
      differ += std::memcmp(chosen_average[p].data(), expected.data(), sizeof(double) * Dim * Dim) == 0 ? 0 : 1;
      inner_read += inner ? 1 : 0;
    }
    CHECK(differ == 0);
    CHECK(inner_read > 0);  // the top face, in bending compression, reads its inner ends
  }

  // Beside a cut-out particle of its face (a crack's mouth) a top particle reads its outer end.
  std::size_t beside = n;
  for (std::size_t p = 0; p < n && beside == n; ++p)
    if (reference[p][1] == highest && reference[p][0] > 0.09 && reference[p][0] < 0.11 &&
        (Dim == 2 || (reference[p][Dim - 1] > 0.02 && reference[p][Dim - 1] < 0.04)))
      beside = p;
  REQUIRE(beside < n);
  std::size_t mouth = n;
  for (Offset b = bonds.begin(beside); b < bonds.end(beside); ++b) {
    const auto k = static_cast<std::size_t>(bonds.neighbor(b));
    if (reference[k][1] == highest && reference[k][0] > reference[beside][0]) mouth = k;
  }
  REQUIRE(mouth < n);
  // Beside a loaded particle of its face (read at its centre: a point load's spikes), likewise.
  FailureStressReadout<Dim> beside_load;
  const auto mouth_loaded = [&](std::size_t k) { return k == mouth; };
  const MatArray<Dim, double> loaded_read =
      beside_load.read(point, x, reference, bonds, &fit, mouth_loaded, settings, larger);
  CHECK(std::memcmp(loaded_read[beside].data(), outer_read[beside].data(), sizeof(double) * Dim * Dim) == 0);
  chosen.mark_cut_out(mouth, n, Vec<Dim>::UnitX());
  const MatArray<Dim, double> after_cut = chosen.read(point, x, reference, bonds, &fit, unloaded, settings, larger);
  CHECK(std::memcmp(after_cut[beside].data(), outer_read[beside].data(), sizeof(double) * Dim * Dim) == 0);
  CHECK((after_cut[beside] - chosen_read[beside]).norm() > 0);
}

// Along a whole face a surface particle's samples are averaged twice (a filter over about +-4 l0);
// on the plane of a crack that crosses the face and has cut out a bonded neighbour (in its slab),
// once, as the interior is: the second pass would spread the crack's own concentration over the
// relaxed face beside it. A bar bent more towards one end is read at the outer ends of its cells
// with averaging; then a top particle (the mouth) is cut out. In 3D, with the crack across the
// bar (normal x), the mouth's neighbour across the width lies in its slab and reads exactly one
// pass over its face: its own sample with the weights of itself and of the mouth, and its other
// bonded top-face neighbours' samples with their bond weights. The top particle beside the mouth
// across the crack plane reads otherwise (two passes). A crack 11 degrees from the face (normal
// (0.2, 1)) has the neighbours along the face in its slab, but does not cross the face: they
// read two passes, in 2D and 3D. So in 2D, where a crack meets the face at one particle, no face
// particle reads one pass. A top particle farther than two bond radii from the mouth reads as
// before the cut, to the bit.
TEST_CASE_TEMPLATE("fracture.failure_stress: a face particle on the plane of a crack across its face is averaged once", T,
                   std::integral_constant<int, 2>, std::integral_constant<int, 3>) {
  constexpr int Dim = T::value;
  const double l0 = 0.01, re = 2.1 * l0, k = 0.03;
  Vec<Dim> upper = Vec<Dim>::Constant(0.06);
  upper[0] = 0.2;
  if (Dim == 3) upper[Dim - 1] = 0.1;  // the particles read and their face neighbours 2 l0 or more inside the sides
  const BondedBar<Dim> bar(upper, l0, re);
  const auto& reference = bar.reference;
  const auto& bonds = bar.bonds;
  const std::size_t n = reference.size();
  const double lowest = bar.lowest, highest = bar.highest, middle = 0.5 * (lowest + highest);
  VecArray<Dim, double> x = reference;
  // Bent, more towards the bar's far end: a strain quadratic along the face, whose averages
  // along it move with each pass.
  for (auto& p : x) p[0] -= k * p[0] * (p[1] - middle) * (p[0] / 0.1) * (p[0] / 0.1);
  DeformationFit<Dim, double> fit;
  fit.build(bonds, l0);
  typename FailureStressReadout<Dim>::Settings settings;
  settings.l0 = l0;
  settings.lame = {6e8, 4e8};
  settings.self_weight = KoshizukaWeight::value(l0, re);
  settings.n0 = full_neighbourhood_weight(bonds, n);
  const MatArray<Dim, double> point(n, Mat<Dim>::Zero());
  const auto unloaded = [](std::size_t) { return false; };
  FailureStressReadout<Dim> readout, samples_only;
  const MatArray<Dim, double> before = readout.read(point, x, reference, bonds, &fit, unloaded, settings);
  typename FailureStressReadout<Dim>::Settings unaveraged = settings;
  unaveraged.average = false;
  const MatArray<Dim, double> sample = samples_only.read(point, x, reference, bonds, &fit, unloaded, unaveraged);

  // The top particle at reference X, or n.
  const auto top_at = [&](const Vec<Dim>& X) {
    for (std::size_t p = 0; p < n; ++p)
      if (reference[p][1] == highest && (reference[p] - X).norm() < 0.1 * l0) return p;
    return n;
  };
  Vec<Dim> mouth_at = Vec<Dim>::Constant(0.055);
  mouth_at[0] = 0.105;
  mouth_at[1] = highest;
  Vec<Dim> along_face = Vec<Dim>::Zero(), across = Vec<Dim>::Zero(), flat = Vec<Dim>::Zero();
  along_face[Dim == 3 ? 2 : 0] = l0;  // across the width in 3D, along the bar in 2D
  across[0] = -l0;
  flat[0] = 0.2;  // a crack 11 degrees from the face
  flat[1] = 1;
  flat.normalize();
  Vec<Dim> far_at = mouth_at;
  far_at[0] = 0.165;
  const std::size_t mouth = top_at(mouth_at), ahead = top_at(mouth_at + along_face), far = top_at(far_at);
  const std::size_t beside = top_at(mouth_at + across);
  REQUIRE(mouth < n);
  REQUIRE(ahead < n);
  REQUIRE(far < n);
  REQUIRE(beside < n);
  REQUIRE((reference[far] - reference[mouth]).norm() > 2 * re);

  // One pass along the face for particle i, the mouth cut out.
  const auto one_pass = [&](std::size_t i) {
    double own = settings.self_weight, weight = 0;
    Mat<Dim> sum = Mat<Dim>::Zero();
    for (Offset b = bonds.begin(i); b < bonds.end(i); ++b) {
      const auto m = static_cast<std::size_t>(bonds.neighbor(b));
      if (reference[m][1] != highest) continue;  // not on its face
      if (m == mouth) {
        own += bonds.weight(b);
        continue;
      }
      sum += bonds.weight(b) * sample[m];
      weight += bonds.weight(b);
    }
    return Mat<Dim>((sum + own * sample[i]) / (weight + own));
  };
  const auto reads_one_pass = [&](const MatArray<Dim, double>& read, std::size_t i) {
    const Mat<Dim> once = one_pass(i);
    return (read[i] - once).norm() < 1e-12 * once.norm();
  };
  const auto read_after_cut = [&](const Vec<Dim>& normal) {
    FailureStressReadout<Dim> cut;
    cut.read(point, x, reference, bonds, &fit, unloaded, settings);  // the first read fixes the faces
    cut.mark_cut_out(mouth, n, normal);
    return cut.read(point, x, reference, bonds, &fit, unloaded, settings);
  };
  CHECK_FALSE(reads_one_pass(before, ahead));
  CHECK_FALSE(reads_one_pass(before, beside));

  const MatArray<Dim, double> crossing = read_after_cut(Vec<Dim>::UnitX());
  if (Dim == 3) CHECK(reads_one_pass(crossing, ahead));
  CHECK_FALSE(reads_one_pass(crossing, beside));  // across the crack plane
  CHECK(std::memcmp(crossing[far].data(), before[far].data(), sizeof(double) * Dim * Dim) == 0);

  const MatArray<Dim, double> along = read_after_cut(flat);
  CHECK(std::abs(across.dot(flat)) < 0.5 * l0);  // beside is in the slab, yet the crack does not cross the face
  CHECK_FALSE(reads_one_pass(along, beside));
  CHECK_FALSE(reads_one_pass(along, ahead));
  CHECK(std::memcmp(along[far].data(), before[far].data(), sizeof(double) * Dim * Dim) == 0);
}

// The screened read averages only where the highest bound over a particle's neighbourhood reaches
// the strength. A bar in tension rising from 0 at the left end to 2 MPa at the right, with noise,
// read at the centres and, with the fit, at the surface (a displacement that stretches the bar as
// the samples do). Three strengths: 1.6 MPa, reached over the right fifth (the screen takes the
// highest bound over every neighbourhood); just under the highest read, reached by a few samples
// (the screen follows them through the bonds); and out of reach (nothing is averaged). Where
// read_screened() computed a tensor it is read()'s to the bit, where it did not sigma_1 of
// read()'s is below the strength (the screen is sound), and complete() fills in read()'s tensors
// to the bit, also after bonds are cut before the read; surface particles read the end of their
// cell with the larger sigma_1 in both reads. A cut between the read and complete() is refused.
// A NaN sample anywhere screens nothing out.
TEST_CASE_TEMPLATE("fracture.failure_stress: the screened read is the full read where failure is possible", T,
                   std::integral_constant<int, 2>, std::integral_constant<int, 3>) {
  constexpr int Dim = T::value;
  const double l0 = 0.01, re = 2.1 * l0, length = 0.2;
  Vec<Dim> upper = Vec<Dim>::Constant(0.04);
  upper[0] = length;
  const auto block = scenes::material_block<Dim>(Vec<Dim>::Zero(), upper, l0);
  const auto& reference = block.positions();
  const std::size_t n = reference.size();
  BondList<Dim> bonds;
  bonds.template build<KoshizukaWeight>(reference, std::vector<std::int32_t>(n, 0), re);
  std::mt19937 random(7);
  std::uniform_real_distribution<double> noise(-5e4, 5e4);
  MatArray<Dim, double> point(n);
  for (std::size_t k = 0; k < n; ++k) {
    Mat<Dim> t;
    for (int a = 0; a < Dim; ++a)
      for (int b = 0; b <= a; ++b) t(a, b) = t(b, a) = noise(random);
    t(0, 0) += 2e6 * reference[k][0] / length;
    point[k] = t;
  }
  // u_x = a X^2 / 2: the strain a X, 2 MPa at the right end under lambda + 2 mu = 1.4 GPa.
  const LameConstants<double> lame{6e8, 4e8};
  const double stretch = 2e6 / (lame.lambda + 2 * lame.mu) / length;
  VecArray<Dim, double> x = reference;
  for (auto& p : x) p[0] += 0.5 * stretch * p[0] * p[0];
  DeformationFit<Dim, double> fit;
  fit.build(bonds, l0);
  typename FailureStressReadout<Dim>::Settings settings;
  settings.l0 = l0;
  settings.self_weight = KoshizukaWeight::value(l0, re);
  settings.lame = lame;
  settings.n0 = full_neighbourhood_weight(bonds, n);
  const auto unloaded = [](std::size_t) { return false; };
  const auto bound = [](const Mat<Dim>& t) { return MaxPrincipalStress::upper_bound<Dim, double>(t); };
  const auto sigma_1 = [](const Mat<Dim>& t) {
    Vec<Dim> direction;
    return MaxPrincipalStress::principal<Dim, double>(t, direction);
  };
  const auto same_bits = [](const Mat<Dim>& a, const Mat<Dim>& b) {
    return std::memcmp(a.data(), b.data(), sizeof(double) * Dim * Dim) == 0;
  };
  // Surface particles read the end of their cell with the larger sigma_1, in both reads.
  const auto larger_end = [&](const Mat<Dim>& outer, const Mat<Dim>& inner) { return sigma_1(inner) > sigma_1(outer); };

  for (const bool at_surface : {false, true}) {
    const DeformationFit<Dim, double>* const fitted = at_surface ? &fit : nullptr;
    for (const int which : {0, 1, 2}) {
      for (const bool cut_some : {false, true}) {
        CAPTURE(at_surface);
        CAPTURE(which);
        CAPTURE(cut_some);
        BondList<Dim> cut = bonds;
        FailureStressReadout<Dim> full, screened;
        full.read(point, x, reference, cut, fitted, unloaded, settings);  // first reads: the same weights
        screened.read(point, x, reference, cut, fitted, unloaded, settings);
        if (cut_some)  // every third particle's first bond, cut after the first read
          for (std::size_t i = 0; i < n; i += 3) cut.cut(cut.begin(i));
        const MatArray<Dim, double> expected =
            full.read(point, x, reference, cut, fitted, unloaded, settings, larger_end);
        if (at_surface && !cut_some) {  // the surface is read outside
          FailureStressReadout<Dim> centres;
          const auto& centre_read = centres.read(point, x, reference, cut, nullptr, unloaded, settings);
          std::size_t read_outside = 0;
          for (std::size_t i = 0; i < n; ++i) read_outside += same_bits(centre_read[i], expected[i]) ? 0 : 1;
          CHECK(read_outside > 0);
        }
        double highest = 0;
        for (const auto& t : expected) highest = std::max(highest, sigma_1(t));
        const double strength = which == 0 ? 1.6e6 : which == 1 ? highest * (1 - 1e-3) : 1e30;
        const auto may_fail = [&](std::size_t, double b) { return !(b < strength); };
        const auto& got = screened.read_screened(point, x, reference, cut, fitted, unloaded, settings, bound, may_fail,
                                                 strength, larger_end);
        std::size_t left_out = 0, differ = 0, unsound = 0, may_fail_count = 0;
        for (std::size_t i = 0; i < n; ++i) {
          may_fail_count += sigma_1(expected[i]) >= strength ? 1 : 0;
          if (screened.evaluated(i)) {
            differ += same_bits(got[i], expected[i]) ? 0 : 1;
          } else {
            ++left_out;
            unsound += sigma_1(expected[i]) < strength ? 0 : 1;
          }
        }
        CHECK(left_out == screened.screened_out());
        // The same particles as the screen over every neighbourhood leaves out: with no floor
        // every sample counts as one that may reach the strength.
        FailureStressReadout<Dim> dense;
        dense.read(point, x, reference, bonds, fitted, unloaded, settings);
        dense.read_screened(point, x, reference, cut, fitted, unloaded, settings, bound, may_fail,
                            -std::numeric_limits<double>::infinity(), larger_end);
        std::size_t other_mask = 0;
        for (std::size_t i = 0; i < n; ++i) other_mask += screened.evaluated(i) == dense.evaluated(i) ? 0 : 1;
        CHECK(other_mask == 0);
        if (which == 2) {
          CHECK(left_out == n);
        } else {
          CHECK(may_fail_count > 0);
          CHECK(left_out > n / 2);  // sigma_xx reaches 1.6 MPa at 0.8 of the length
          CHECK(left_out < n);
        }
        CHECK(differ == 0);
        CHECK(unsound == 0);
        screened.complete(point, cut, larger_end);
        differ = 0;
        for (std::size_t i = 0; i < n; ++i) differ += same_bits(got[i], expected[i]) ? 0 : 1;
        CHECK(differ == 0);
        CHECK(screened.screened_out() == 0);
      }
    }
  }
  const double strength = 1.6e6;
  const auto may_fail = [&](std::size_t, double b) { return !(b < strength); };

  // A bond cut between the screened read and complete(): completing would mix the two states.
  {
    FailureStressReadout<Dim> screened;
    screened.read_screened(point, x, reference, bonds, nullptr, unloaded, settings, bound, may_fail, strength);
    REQUIRE(screened.screened_out() > 0);
    Offset intact = bonds.begin(1);
    while (intact < bonds.end(1) && !bonds.intact(intact)) ++intact;
    REQUIRE(intact < bonds.end(1));
    bonds.cut(intact);
    CHECK_THROWS_AS(screened.complete(point, bonds), InvalidInput);
  }

  // A read whose ends are chosen by a caller's inner_end is completed with it, not without.
  {
    FailureStressReadout<Dim> screened;
    screened.read_screened(point, x, reference, bonds, &fit, unloaded, settings, bound, may_fail, 1e30, larger_end);
    REQUIRE(screened.screened_out() > 0);
    CHECK_THROWS_AS(screened.complete(point, bonds), InvalidInput);
  }

  // A NaN at the left end, where everything else would be screened out.
  std::size_t nan_at = 0;
  for (std::size_t k = 0; k < n; ++k)
    if (x[k][0] < x[nan_at][0]) nan_at = k;
  point[nan_at](0, 1) = std::numeric_limits<double>::quiet_NaN();
  FailureStressReadout<Dim> screened;
  screened.read_screened(point, x, reference, bonds, nullptr, unloaded, settings, bound, may_fail, strength);
  CHECK(screened.screened_out() == 0);
}

}
