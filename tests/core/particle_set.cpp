// SPDX-License-Identifier: BSD-3-Clause
#include <doctest/doctest.h>

#include <cmath>

#include "mpsfsi/core/particle_set.hpp"

using namespace mpsfsi;

TEST_SUITE("core") {

TEST_CASE_TEMPLATE("core.particle_set: fields grow, permute and validate together", V, Vec<2>, Vec<3>) {
  constexpr int Dim = static_cast<int>(V::RowsAtCompileTime);
  ParticleSet<Dim> set;
  CHECK(set.empty());
  auto p = set.template add_field<double>("pressure");
  auto f = set.template add_field<Vec<Dim>>("force");
  auto s = set.template add_field<Mat<Dim>>("stress");
  auto c = set.template add_field<std::int32_t>("colour");
  for (int i = 0; i < 4; ++i) set.add(Vec<Dim>::Constant(i), i % 2 ? ParticleKind::wall : ParticleKind::fluid);
  REQUIRE(set.size() == 4);
  CHECK(set.field(p).size() == 4);
  CHECK(set.field(f)[3] == Vec<Dim>::Zero());
  CHECK(set.field(s)[3] == Mat<Dim>::Zero());
  CHECK(set.field(c)[3] == 0);
  CHECK(set.field_name(f) == "force");
  for (int i = 0; i < 4; ++i) {
    set.field(p)[i] = 10.0 * i;
    set.field(c)[i] = i;
  }
  set.permute({3, 2, 1, 0});
  CHECK(set.positions()[0] == Vec<Dim>::Constant(3));
  CHECK(set.field(p)[0] == 30.0);
  CHECK(set.field(c)[0] == 3);
  CHECK(set.kinds()[0] == ParticleKind::wall);
  CHECK(set.ids()[0] == 3);
  set.validate();

  int seen = 0;
  set.for_each_scalar_field([&](const std::string& name, const std::vector<double>& v) {
    CHECK(name == "pressure");
    CHECK(v.size() == 4);
    ++seen;
  });
  CHECK(seen == 1);

  SUBCASE("mismatched field size is named") {
    set.field(p).pop_back();
    CHECK_THROWS_WITH_AS(set.validate(), doctest::Contains("pressure"), InvalidInput);
  }
  SUBCASE("non-finite position is named with its particle") {
    set.positions()[2][0] = std::nan("");
    CHECK_THROWS_WITH_AS(set.validate(), doctest::Contains("particle 2"), InvalidInput);
  }
  SUBCASE("bad permutation") { CHECK_THROWS_AS(set.permute({0, 1}), InvalidInput); }
}

TEST_CASE("core.particle_set: ids are never reused") {
  ParticleSet<2> set(3);
  set.permute({2, 1, 0});
  set.resize(1);  // keeps the particle with id 2
  set.resize(3);  // new particles get fresh ids, never 2 a second time
  CHECK(set.ids()[0] == 2);
  CHECK(set.ids()[1] == 3);
  CHECK(set.ids()[2] == 4);
  CHECK_THROWS_AS(set.permute({0, 1, 7}), InvalidInput);
}

TEST_CASE("core.particle_set: holds a million particles") {
  ParticleSet<3> set(1000000);
  auto p = set.add_field<double>("pressure");
  CHECK(set.size() == 1000000);
  CHECK(set.field(p).size() == 1000000);
  CHECK(set.ids().back() == 999999);
}

}  // TEST_SUITE
