// SPDX-License-Identifier: BSD-3-Clause
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <vector>

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
  std::vector<std::uint8_t> surface, surface_count, surface_centroid;
  NumberDensitySurface::detect(set.positions(), set.kinds(), all, n, c.n0, 0.97, l0, re, surface);
  NeighborCountSurface::detect(set.positions(), set.kinds(), all, n, c.n0, 0.97, l0, re, surface_count);
  CentroidDeviationSurface<KoshizukaWeight>::detect(set.positions(), set.kinds(), all, n, c.n0, 0.97, l0, re,
                                                    surface_centroid);
  std::size_t flagged = 0, flagged_count = 0, flagged_centroid = 0, top_row = 0, deep = 0, deep_flagged = 0;
  for (std::size_t i = 0; i < set.size(); ++i) {
    flagged += surface[i];
    flagged_count += surface_count[i];
    flagged_centroid += surface_centroid[i];
    CHECK(surface_count[i] <= surface[i]);  // both two-stage tests only remove flags
    CHECK(surface_centroid[i] <= surface[i]);
    const bool top = set.kinds()[i] == ParticleKind::fluid && set.positions()[i][Dim - 1] > side - l0 + 0.1 * l0 - 0.2;
    if (top) {
      ++top_row;
      CHECK(surface[i] == 1);  // the top layer is free surface for all three
      CHECK(surface_count[i] == 1);
      CHECK(surface_centroid[i] == 1);
    }
    // More than re below the top, fluid, wall or dummy particles surround a particle on every side:
    // the jitter (up to 0.1 l0 per coordinate) lowers n below 0.97 n0 for some, but the neighbours'
    // centroid stays within 0.2 l0 of them here, so the centroid test flags none.
    if (set.kinds()[i] != ParticleKind::dummy && set.positions()[i][Dim - 1] < side - l0 - re) {
      ++deep;
      deep_flagged += surface[i];
      CHECK(surface_centroid[i] == 0);
    }
    if (set.kinds()[i] == ParticleKind::dummy) {
      CHECK(surface[i] == 0);
      CHECK(surface_centroid[i] == 0);
    }
  }
  MESSAGE(Dim << "D: n < 0.97 n0 flags " << flagged << " (" << deep_flagged << " of " << deep
              << " more than re below the top), with the neighbour count " << flagged_count
              << ", with the centroid deviation " << flagged_centroid << ", top layer " << top_row);

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

// WallCondition::neumann: with ghost pressures P_i + G . r for the dummies and no source, the
// rows of every unknown whose neighbourhood is complete (fluid, wall or dummy at every lattice
// site within re) are satisfied exactly by the linear field with gradient G: the MPS Laplacian of
// a linear field vanishes on a complete lattice neighbourhood. A lattice tank under a lid (dummy
// rows above and below), G = rho g: the water at rest between floor and lid is hydrostatic. The
// default (dummies left out) is not: its wall rows see half a neighbourhood.
TEST_CASE("fluid.ppe: Neumann ghosts make a hydrostatic field solve the rows of walls and fluid") {
  const double l0 = 1.0, re = 3.1, rho_g = 9810;
  ParticleSet<2> set;
  scenes::add_block<2, double>(set, Vec<2>::Zero(), Vec<2>(14, 8), l0, ParticleKind::fluid);
  for (int row = 0; row < 4; ++row)  // a floor and a lid: one wall row against the water, dummies behind
    for (int col = -4; col < 18; ++col) {
      const auto kind = row == 0 ? ParticleKind::wall : ParticleKind::dummy;
      set.add(Vec<2>((col + 0.5) * l0, -(row + 0.5) * l0), kind);
      set.add(Vec<2>((col + 0.5) * l0, 8 + (row + 0.5) * l0), kind);
    }
  CellListSearch<2> search(re);
  search.build(set.positions());
  NeighborList all;
  search.self_query(set.positions(), all);
  const auto c = ideal_lattice_constants<2, KoshizukaWeight>(l0, re);
  // The end columns of the water are at P = 0 (Dirichlet), which anchors the system; the rows
  // checked lie more than re from them.
  std::vector<std::uint8_t> surface(set.size(), 0);
  for (std::size_t i = 0; i < set.size(); ++i)
    surface[i] = set.kinds()[i] == ParticleKind::fluid && (set.positions()[i][0] < 1 || set.positions()[i][0] > 13);
  const std::vector<double> source(set.size(), 0.0);
  VecArray<2> gradient(set.size(), Vec<2>(0, -rho_g));  // P rises downwards: rho g
  PpeAssembler<KoshizukaWeight, 2, double> ppe;
  PpeMatrix a_ghost, a_plain;
  PpeVector b_ghost, b_plain;
  ppe.assemble(set.positions(), set.kinds(), surface, all, c, source, a_ghost, b_ghost, false, &gradient);
  ppe.assemble(set.positions(), set.kinds(), surface, all, c, source, a_plain, b_plain);
  CHECK((a_ghost - a_plain).norm() == 0);  // the ghosts go to the right-hand side only
  PpeVector p(static_cast<Eigen::Index>(ppe.num_unknowns()));
  for (std::size_t r = 0; r < ppe.num_unknowns(); ++r)
    p[static_cast<Eigen::Index>(r)] = rho_g * (10 - set.positions()[static_cast<std::size_t>(ppe.particle_of_row()[r])][1]);
  const PpeVector residual_ghost = a_ghost * p - b_ghost, residual_plain = a_plain * p - b_plain;
  double worst_ghost = 0, worst_wall_plain = 0;
  int checked = 0;
  for (std::size_t r = 0; r < ppe.num_unknowns(); ++r) {
    const auto i = static_cast<std::size_t>(ppe.particle_of_row()[r]);
    const double x = set.positions()[i][0];
    if (x < 4.5 || x > 9.5) continue;  // more than re from the Dirichlet end columns
    worst_ghost = std::max(worst_ghost, std::abs(residual_ghost[static_cast<Eigen::Index>(r)]));
    if (set.kinds()[i] == ParticleKind::wall)
      worst_wall_plain = std::max(worst_wall_plain, std::abs(residual_plain[static_cast<Eigen::Index>(r)]));
    ++checked;
  }
  REQUIRE(checked > 50);
  // A row's terms are of order rho g / l0 (l0 = 1 here): round-off, against a residual of that
  // order where the dummies are left out.
  CHECK(worst_ghost <= 1e-10 * rho_g);
  CHECK(worst_wall_plain > 0.1 * rho_g);
}

TEST_CASE("fluid.ppe: a row is sorted by column with its values, whatever its runs") {
  // Rows as the assembly produces them: ascending runs of columns, each entry's value tied to
  // its column. Lengths either side of the insertion sort's limit, one to many runs.
  detail::RowSortBuffer buffer;
  buffer.reserve_row(200);
  for (const int length : {0, 1, 5, 63, 64, 65, 120, 200}) {
    for (const int runs : {1, 2, 3, 7, 27, 200}) {
      std::vector<int> cols(static_cast<std::size_t>(length));
      for (int p = 0; p < length; ++p) {
        const int run = p % runs;  // entry p goes to run p mod runs ...
        const int within = p / runs;
        cols[static_cast<std::size_t>(p)] = 1000 * within + run;  // ... distinct columns
      }
      // Concatenate the runs, each ascending, runs in descending order of their first column.
      std::vector<int> row;
      for (int run = runs - 1; run >= 0; --run)
        for (int p = 0; p < length; ++p)
          if (p % runs == run) row.push_back(cols[static_cast<std::size_t>(p)]);
      std::vector<double> vals(row.size());
      for (std::size_t p = 0; p < row.size(); ++p) vals[p] = 0.5 * row[p];
      detail::sort_row_by_column(row.data(), vals.data(), length, buffer);
      CAPTURE(length);
      CAPTURE(runs);
      std::sort(cols.begin(), cols.end());
      CHECK(row == cols);
      for (std::size_t p = 0; p < row.size(); ++p) CHECK(vals[p] == 0.5 * row[p]);
    }
  }
}

}  // TEST_SUITE
