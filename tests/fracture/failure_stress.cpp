// SPDX-License-Identifier: BSD-3-Clause
#include <doctest/doctest.h>

#include "mpsfsi/fracture/failure_stress.hpp"
#include "mpsfsi/kernels/weight.hpp"
#include "mpsfsi/scenes/solid_block.hpp"

using namespace mpsfsi;

TEST_SUITE("fracture") {

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
  readout.mark_cut_out(k, x.size());
  CHECK(read_at_i() == doctest::Approx(1e6 * (self + w_k) / (self + all)).epsilon(1e-12));
}

}
