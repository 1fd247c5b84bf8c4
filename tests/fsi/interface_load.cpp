// SPDX-License-Identifier: BSD-3-Clause
#include <doctest/doctest.h>

#include "mpsfsi/fsi/interface_acceleration.hpp"
#include "mpsfsi/fsi/interface_load.hpp"
#include "mpsfsi/core/cell_list_search.hpp"
#include "mpsfsi/kernels/weight.hpp"
#include "mpsfsi/scenes/solid_block.hpp"

using namespace mpsfsi;

namespace {

// A fluid lattice above y = 0 (width w, height h) and a row of structure particles below it.
struct FlatInterface {
  double l0 = 0.01, re = 0.021;
  ParticleSet<2> fluid;
  VecArray<2> structure, normal;
  std::vector<std::uint8_t> surface;
  std::vector<double> pressure;
  NeighborList candidates;

  explicit FlatInterface(double w = 0.2, double h = 0.1, double structure_from = 0.05, double structure_to = 0.15) {
    fluid = scenes::material_block<2>(Vec<2>(0, 0), Vec<2>(w, h), l0);
    for (auto& k : fluid.kinds()) k = ParticleKind::fluid;
    for (double x = structure_from + l0 / 2; x < structure_to; x += l0) {
      structure.push_back(Vec<2>(x, -l0 / 2));
      normal.push_back(Vec<2>(0, 1));
      surface.push_back(1);
    }
    CellListSearch<2, double> search(re + l0 / 2);
    search.build(fluid.positions());
    search.query(structure, candidates, QueryOptions{});
  }
};

}  // namespace

TEST_SUITE("fsi") {

TEST_CASE("fsi.interface_load: a uniform pressure on a wetted face gives P l0 along -n") {
  FlatInterface s;
  s.pressure.assign(s.fluid.size(), 1234.0);
  VecArray<2> force;
  std::vector<double> p_if;
  const double full = full_wetting_weight<KoshizukaWeight, 2, double>(s.l0, s.re);
  interface_loads<KoshizukaWeight>(s.structure, s.normal, s.surface, s.fluid, s.pressure, s.candidates, s.l0, s.re,
                                   full, force, p_if);
  for (std::size_t i = 0; i < s.structure.size(); ++i) {
    CHECK(p_if[i] == doctest::Approx(1234.0).epsilon(1e-12));
    CHECK((force[i] - Vec<2>(0, -1234.0 * s.l0)).norm() < 1e-9);
  }
}

TEST_CASE("fsi.interface_load: eq 18 is a weighted average, exact for a field linear along the face") {
  FlatInterface s;
  s.pressure.resize(s.fluid.size());
  for (std::size_t j = 0; j < s.fluid.size(); ++j) s.pressure[j] = 1000 + 5000 * s.fluid.positions()[j][0];
  VecArray<2> force;
  std::vector<double> p_if;
  interface_loads<KoshizukaWeight>(s.structure, s.normal, s.surface, s.fluid, s.pressure, s.candidates, s.l0, s.re,
                                   0.0, force, p_if);
  // The neighbourhood of x_IF is symmetric along x, so the average is the value at x_IF.
  for (std::size_t i = 0; i < s.structure.size(); ++i)
    CHECK(p_if[i] == doctest::Approx(1000 + 5000 * s.structure[i][0]).epsilon(1e-12));
}

TEST_CASE("fsi.interface_load: partial wetting scales the load, interior and dry particles carry none") {
  // Structure row wider than the water: the ends stick out under dry space.
  FlatInterface s(0.1, 0.05, -0.05, 0.15);
  s.pressure.assign(s.fluid.size(), 100.0);
  s.surface[3] = 0;  // an interior particle
  VecArray<2> force;
  std::vector<double> p_if;
  const double full = full_wetting_weight<KoshizukaWeight, 2, double>(s.l0, s.re);
  interface_loads<KoshizukaWeight>(s.structure, s.normal, s.surface, s.fluid, s.pressure, s.candidates, s.l0, s.re,
                                   full, force, p_if);
  double total = 0;
  for (std::size_t i = 0; i < s.structure.size(); ++i) {
    const double x = s.structure[i][0];
    if (i == 3 || x < -0.02 || x > 0.12) CHECK(force[i].norm() == 0);
    if (x > 0.02 && x < 0.08) CHECK(p_if[i] == doctest::Approx(100.0));
    if (x < 0 || x > 0.1) CHECK(p_if[i] < 100.0 * 0.5);
    total -= force[i][1];
  }
  // The wetted span is 0.1 m: what the dry elements next to it gain, the wetted edge elements
  // lose (the smearing is symmetric), so the total is conserved; measured 0.03 %.
  CHECK(total == doctest::Approx(100.0 * 0.1).epsilon(0.01));
  // As printed (no correction), every element that sees any fluid gets the full pressure, and the
  // total exceeds the water's by the dry elements in range (two each side, one of them marked
  // interior above): +30 %.
  interface_loads<KoshizukaWeight>(s.structure, s.normal, s.surface, s.fluid, s.pressure, s.candidates, s.l0, s.re,
                                   0.0, force, p_if);
  double uncorrected = 0;
  for (std::size_t i = 0; i < s.structure.size(); ++i) {
    if (p_if[i] > 0) CHECK(p_if[i] == doctest::Approx(100.0));
    uncorrected -= force[i][1];
  }
  CHECK(uncorrected == doctest::Approx(100.0 * 0.13).epsilon(1e-9));
}

TEST_CASE("fsi.interface_acceleration: fluid next to the interface takes its acceleration, the rest none") {
  FlatInterface s;
  VecArray<2> a(s.structure.size(), Vec<2>(0.5, -2.0)), out;
  std::vector<double> scratch;
  interface_accelerations<KoshizukaWeight>(s.structure, a, s.surface, s.fluid, s.candidates, s.re, out, scratch);
  for (std::size_t j = 0; j < s.fluid.size(); ++j) {
    const Vec<2> x = s.fluid.positions()[j];
    if (x[1] < 0.01 && x[0] > 0.06 && x[0] < 0.14) CHECK((out[j] - Vec<2>(0.5, -2.0)).norm() < 1e-12);
    if (x[1] > 0.03) CHECK(out[j].norm() == 0);
  }
}

}  // TEST_SUITE
