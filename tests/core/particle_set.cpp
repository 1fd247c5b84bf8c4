// SPDX-License-Identifier: BSD-3-Clause
#include <doctest/doctest.h>

#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

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

TEST_CASE("core.particle_set: a packed particle unpacks with every field and its id") {
  ParticleSet<3> from;
  const auto s = from.add_field<double>("s");
  const auto v = from.add_field<Vec<3, double>>("v");
  const auto t = from.add_field<Mat<3, double>>("t");
  const auto k = from.add_field<std::int32_t>("k");
  for (int i = 0; i < 3; ++i) from.add(Vec<3, double>(i, 2 * i, 3 * i), ParticleKind::solid, Vec<3, double>(-i, 0, i));
  from.number_ids_from(100);
  CHECK(from.ids() == std::vector<Index>{100, 101, 102});
  from.field(s)[1] = 1.5;
  from.field(v)[1] = Vec<3, double>(1, 2, 3);
  from.field(t)[1] = Mat<3, double>::Constant(4);
  from.field(k)[1] = -7;
  CHECK(from.packed_size() == 2 * 24 + 1 + 4 + 8 + 24 + 72 + 4);
  std::vector<unsigned char> bytes(from.packed_size());
  from.pack(1, bytes.data());

  ParticleSet<3> to;
  to.add_field<double>("s");
  to.add_field<Vec<3, double>>("v");
  to.add_field<Mat<3, double>>("t");
  to.add_field<std::int32_t>("k");
  to.add(Vec<3, double>::Zero());
  to.unpack(bytes.data());
  REQUIRE(to.size() == 2);
  CHECK(to.ids()[1] == 101);
  CHECK(to.positions()[1] == Vec<3, double>(1, 2, 3));
  CHECK(to.velocities()[1] == Vec<3, double>(-1, 0, 1));
  CHECK(to.kinds()[1] == ParticleKind::solid);
  CHECK(to.field(s)[1] == 1.5);
  CHECK(to.field(v)[1] == Vec<3, double>(1, 2, 3));
  CHECK(to.field(t)[1] == Mat<3, double>::Constant(4));
  CHECK(to.field(k)[1] == -7);
  CHECK(to.add(Vec<3, double>::Zero()) == 2);
  CHECK(to.ids()[2] == 102);  // new ids continue after the largest one received
  to.unpack_into(0, bytes.data());
  CHECK(to.ids()[0] == 101);
  CHECK(to.field(t)[0] == Mat<3, double>::Constant(4));
  CHECK_THROWS_AS(from.number_ids_from(-1), InvalidInput);
  CHECK_THROWS_AS(from.number_ids_from(std::numeric_limits<Index>::max() - 1), InvalidInput);
}

}  // TEST_SUITE
