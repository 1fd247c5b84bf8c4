// SPDX-License-Identifier: BSD-3-Clause
#include <doctest/doctest.h>

#include <cmath>

#include "mpsfsi/core/cell_list_search.hpp"
#include "mpsfsi/kernels/divergence.hpp"
#include "mpsfsi/kernels/gradient.hpp"
#include "mpsfsi/kernels/gradient_correction.hpp"
#include "mpsfsi/scenes/lattice.hpp"

using namespace mpsfsi;

TEST_SUITE("kernels") {

TEST_CASE("kernels.gradient: coincident particles give finite results, not NaN") {
  auto set = scenes::lattice_box<2>(Vec<2>(0, 0), Vec<2>(1, 1), 0.1);
  set.add(set.positions()[60]);  // a second particle on top of particle 60
  CellListSearch<2> search(0.21);
  search.build(set.positions());
  NeighborList list;
  search.self_query(set.positions(), list);
  const auto c = ideal_lattice_constants<2, KoshizukaWeight>(0.1, 0.21);
  std::vector<double> phi(set.size());
  VecArray<2> u(set.size());
  for (std::size_t i = 0; i < set.size(); ++i) {
    phi[i] = 3.0 * set.positions()[i][0];
    u[i] = set.positions()[i];
  }
  KhayyerGotohCorrection<2> kg;
  kg.update<KoshizukaWeight>(set.positions(), list, c);
  VecArray<2> g;
  std::vector<double> div;
  gradient<KoshizukaWeight>(set.positions(), list, phi, c, kg, g);
  divergence<KoshizukaWeight>(set.positions(), list, u, c, kg, div);
  for (std::size_t i = 0; i < set.size(); ++i) {
    CHECK(g[i].allFinite());
    CHECK(std::isfinite(div[i]));
  }
  // The pair's other neighbours are intact, so the corrected gradient stays exact there.
  CHECK(std::abs(g[60][0] - 3.0) < 3e-10);
}

}  // TEST_SUITE
