// SPDX-License-Identifier: BSD-3-Clause
// A downstream program: picks dimension and kernels at compile time, builds a neighbour list and
// evaluates number density. Exits non-zero if the result is wrong.
#include <cmath>
#include <cstdio>

#include <mpsfsi/mpsfsi.hpp>

int main() {
  using namespace mpsfsi;
  const double l0 = 1.0;
  const double re = 2.1 * l0;
  ParticleSet<2> particles = scenes::lattice_box<2>(Vec<2>(0, 0), Vec<2>(20, 20), l0);
  CellListSearch<2> search(re);
  NeighborList list;
  search.build(particles.positions());
  search.self_query(particles.positions(), list);
  std::vector<double> n(particles.size());
  number_density<KoshizukaWeight>(particles.positions(), list, re, n);
  const double n0 = ideal_lattice_constants<2, KoshizukaWeight>(l0, re).n0;
  const std::size_t centre = 10 * 21 + 10;
  std::printf("mpsfsi %s: n(centre) = %.12f, n0 = %.12f\n", version_string, n[centre], n0);
  return std::abs(n[centre] - n0) < 1e-12 * n0 ? 0 : 1;
}
