// SPDX-License-Identifier: BSD-3-Clause
#include <doctest/doctest.h>

#include <cstdint>
#include <string>
#include <vector>

#include "mpsfsi/fracture/fracture_process.hpp"
#include "mpsfsi/scenes/solid_block.hpp"
#include "mpsfsi/solid/elastic_solver.hpp"
#include "mpsfsi/solid/fragments.hpp"
#include "support/ice.hpp"

using namespace mpsfsi;

TEST_SUITE("fracture") {

TEST_CASE_TEMPLATE("fracture.fragments: an imposed crack splits a bar into the two pieces on its sides", T,
                   std::integral_constant<int, 2>, std::integral_constant<int, 3>) {
  constexpr int Dim = T::value;
  const double l0 = 0.01;
  Vec<Dim> upper = Vec<Dim>::Constant(0.04);
  upper[0] = 0.1;
  ElasticSolver<Dim, BrittleSolidPolicies<Dim>> s(scenes::material_block<Dim>(Vec<Dim>::Zero(), upper, l0),
                                                   test::case02_ice<Dim>(l0));
  const auto& x = s.particles().positions();
  const std::size_t n = x.size();

  const Fragments whole = find_fragments(s.bonds());
  CHECK(whole.count() == 1);
  CHECK(whole.sizes[0] == n);

  // Crack the column at x = 0.055 along x: it keeps its bonds to the right (its + side) and loses
  // those to the left, so the pieces are x < 0.05 (5 columns) and x > 0.05 (5 columns).
  for (std::size_t i = 0; i < n; ++i)
    if (std::abs(x[i][0] - 0.055) < 1e-9) s.impose_crack(i, Vec<Dim>::UnitX());
  const Fragments split = find_fragments(s.bonds());
  REQUIRE(split.count() == 2);
  CHECK(split.sizes[0] == n / 2);
  CHECK(split.sizes[1] == n / 2);
  CHECK(split.count_larger_than(n / 10) == 2);
  for (std::size_t i = 0; i < n; ++i) CHECK(split.label[i] == (x[i][0] < 0.05 ? 0 : 1));

  // Leaving out every bond that crosses x = 0.08 too gives three pieces (the diagnostic form).
  const auto& bonds = s.bonds();
  const auto not_across = [&](std::size_t i, Offset b) {
    const auto j = static_cast<std::size_t>(bonds.neighbor(b));
    return (x[i][0] < 0.08) == (x[j][0] < 0.08);
  };
  const Fragments three = find_fragments(bonds, not_across);
  CHECK(three.count() == 3);
  CHECK(three.sizes[2] == n / 5);

  // The solid's output carries the labels as the integer field "fragment".
  std::vector<Index> written;
  s.output().for_each_int_field([&](const std::string& name, const auto& values) {
    if (name == "fragment") written.assign(values.begin(), values.end());
  });
  CHECK(written == split.label);
}

TEST_CASE("fracture.fragments: separate bodies and a particle with every bond cut are fragments of their own") {
  const double l0 = 0.01;
  ParticleSet<2> set = scenes::material_block<2>(Vec<2>::Zero(), Vec<2>(0.05, 0.05), l0);
  const std::size_t first = set.size();
  for (std::size_t i = 0; i < first; ++i) set.add(set.positions()[i] + Vec<2>(0.1, 0), ParticleKind::solid);
  std::vector<std::int32_t> body(set.size(), 0);
  for (std::size_t i = first; i < set.size(); ++i) body[i] = 1;
  ElasticSolver<2, BrittleSolidPolicies<2>> s(set, test::case02_ice<2>(l0), body);
  CHECK(find_fragments(s.bonds()).count() == 2);

  // Isolate the centre particle of the first body by cutting all its bonds.
  const std::size_t centre = 12;  // (2, 2) of the 5 x 5 block
  REQUIRE((s.particles().positions()[centre] - Vec<2>(0.025, 0.025)).norm() < 1e-12);
  for (int k = 0; k < 2; ++k) {
    Vec<2> nrm = Vec<2>::Zero();
    nrm[k] = 1;
    s.impose_crack(centre, nrm);
    s.impose_crack(centre, -nrm);
  }
  REQUIRE(s.bonds().intact_count(centre) == 0);
  const Fragments f = find_fragments(s.bonds());
  CHECK(f.count() == 3);
  CHECK(f.label[centre] == 1);  // labels follow the first particle of each fragment
  CHECK(f.sizes[1] == 1);
  CHECK(f.count_larger_than(1) == 2);
}

}  // TEST_SUITE
