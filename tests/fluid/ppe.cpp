// SPDX-License-Identifier: BSD-3-Clause
#include <doctest/doctest.h>

#include "mpsfsi/core/cell_list_search.hpp"
#include "mpsfsi/core/filter_neighbors.hpp"
#include "mpsfsi/fluid/free_surface.hpp"
#include "mpsfsi/fluid/ppe.hpp"
#include "mpsfsi/kernels/number_density.hpp"
#include "mpsfsi/scenes/lattice.hpp"
#include "mpsfsi/scenes/tank.hpp"

using namespace mpsfsi;

TEST_SUITE("fluid") {

TEST_CASE_TEMPLATE("fluid.ppe: the assembled matrix is symmetric, sorted, diagonally dominant; surfaces found", V, Vec<2>,
                   Vec<3>) {
  constexpr int Dim = static_cast<int>(V::RowsAtCompileTime);
  const double l0 = 1.0, re = 3.1;
  ParticleSet<Dim> set;
  const double side = Dim == 2 ? 12 : 6;
  scenes::add_block<Dim, double>(set, Vec<Dim>::Zero(), Vec<Dim>::Constant(side), l0, ParticleKind::fluid);
  scenes::add_tank<Dim, double>(set, Vec<Dim>::Constant(side), l0);
  scenes::jitter(set, 0.1);
  CellListSearch<Dim> search(re);
  search.build(set.positions());
  NeighborList all, list;
  search.self_query(set.positions(), all);
  filter_neighbors(all, [&](Index j) { return set.kinds()[static_cast<std::size_t>(j)] != ParticleKind::dummy; }, list);
  const auto c = ideal_lattice_constants<Dim, KoshizukaWeight>(l0, re);
  std::vector<double> n;
  number_density<KoshizukaWeight>(set.positions(), all, re, n);
  std::vector<std::uint8_t> surface, surface_count;
  NumberDensitySurface::detect(set.positions(), set.kinds(), all, n, c.n0, 0.97, l0, re, surface);
  NeighborCountSurface::detect(set.positions(), set.kinds(), all, n, c.n0, 0.97, l0, re, surface_count);
  std::size_t flagged = 0, flagged_count = 0, top_row = 0;
  for (std::size_t i = 0; i < set.size(); ++i) {
    flagged += surface[i];
    flagged_count += surface_count[i];
    const bool top = set.kinds()[i] == ParticleKind::fluid && set.positions()[i][Dim - 1] > side - l0 + 0.1 * l0 - 0.2;
    if (top) {
      ++top_row;
      CHECK(surface[i] == 1);  // the top layer is free surface for both
      CHECK(surface_count[i] == 1);
    }
    if (set.kinds()[i] == ParticleKind::dummy) CHECK(surface[i] == 0);
  }
  CHECK(flagged_count <= flagged);  // the count test only removes flags
  MESSAGE(Dim << "D: n < 0.97 n0 flags " << flagged << ", with the neighbour count " << flagged_count << ", top layer "
              << top_row);

  std::vector<double> source(set.size(), 1.0);
  PpeAssembler<KoshizukaWeight, Dim, double> ppe;
  PpeMatrix a;
  PpeVector b;
  ppe.assemble(set.positions(), set.kinds(), surface, list, c, source, a, b);
  REQUIRE(ppe.num_unknowns() > 0);
  const PpeMatrix at = a.transpose();
  CHECK((PpeMatrix(a - at)).norm() <= 1e-12 * a.norm());
  for (int r = 0; r < a.rows(); ++r) {
    double diag = 0, off = 0;
    for (int k = a.outerIndexPtr()[r]; k < a.outerIndexPtr()[r + 1]; ++k) {
      if (k > a.outerIndexPtr()[r]) CHECK(a.innerIndexPtr()[k] > a.innerIndexPtr()[k - 1]);
      if (a.innerIndexPtr()[k] == r) diag = a.valuePtr()[k];
      else off += std::abs(a.valuePtr()[k]);
    }
    CHECK(diag > 0);
    CHECK(diag >= off * (1 - 1e-12));
    CHECK(b[r] == -1.0);
  }
}

}  // TEST_SUITE
