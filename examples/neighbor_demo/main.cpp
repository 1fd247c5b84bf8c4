// SPDX-License-Identifier: BSD-3-Clause
// Demo of mpsfsi's foundation on a 2D water column: neighbour search (cell list and kd-tree),
// number density and free-surface flags, the standard and the Khayyer-Gotoh corrected gradient
// of the hydrostatic pressure, and the Laplacian. Writes a VTU (+ PVD) for ParaView and a CSV
// of the operator errors. `neighbor_demo --help` lists the options.
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>

#include <mpsfsi/mpsfsi.hpp>

#include "common/case_options.hpp"
#include "common/output_folder.hpp"

using namespace mpsfsi;

namespace {

struct Options {
  double l0 = 0.005;      // particle spacing (m)
  double jitter = 0.1;    // random displacement, fraction of l0
  std::string out = "out/neighbor_demo";
};

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace

int main(int argc, char** argv) try {
  Options opt;
  mpsfsi_examples::CaseOptions cli("neighbor_demo", "Neighbour search and MPS operators on a 2D water column");
  cli.add("--l0", opt.l0, "particle spacing", "m")->check(mpsfsi_examples::positive());
  cli.add("--jitter", opt.jitter, "random displacement of each particle, as a fraction of l0 (at most 0.45: no two particles meet)")
      ->check(CLI::Range(0.0, 0.45));
  cli.add("--out", opt.out, "output folder");
  if (const auto code = cli.parse_or_exit_code(argc, argv)) return *code;
  if (cli.print_case_if_requested()) return 0;
  const double width = 0.25, height = 0.5, rho = 1000.0, g = 9.81;
  const double re = 2.1 * opt.l0, re_lap = 3.1 * opt.l0;

  ParticleSet<2> water = scenes::lattice_box<2>(Vec<2>(0, 0), Vec<2>(width, height), opt.l0);
  scenes::jitter(water, opt.jitter * opt.l0);
  auto n_field = water.add_field<double>("number_density");
  auto p_field = water.add_field<double>("pressure");
  auto surface = water.add_field<std::int32_t>("free_surface");
  auto grad_kg = water.add_field<Vec<2>>("grad_p_corrected");
  auto grad_std = water.add_field<Vec<2>>("grad_p_standard");

  // Neighbour lists: sort the particles by cell once, then one list with the larger radius
  // serves every operator (weights vanish beyond each operator's own re).
  CellListSearch<2> cells(re_lap);
  reorder_by_cell(water, cells);
  NeighborList list;
  QueryOptions with_distances;
  with_distances.store_distances = true;
  auto t0 = std::chrono::steady_clock::now();
  cells.build(water.positions());
  cells.self_query(water.positions(), list, with_distances);
  const double t_cells = seconds_since(t0);
  KdTreeSearch<2> tree(re_lap);
  NeighborList tree_list;
  t0 = std::chrono::steady_clock::now();
  tree.build(water.positions());
  tree.self_query(water.positions(), tree_list);
  const double t_tree = seconds_since(t0);

  const auto c = ideal_lattice_constants<2, KoshizukaWeight>(opt.l0, re);
  const auto c_lap = ideal_lattice_constants<2, KoshizukaWeight>(opt.l0, re_lap);

  // Number density (eq 12) and the classic free-surface test n < 0.97 n0.
  auto& n = water.field(n_field);
  number_density<KoshizukaWeight>(water.positions(), list, re, n);
  std::size_t n_surface = 0;
  for (std::size_t i = 0; i < water.size(); ++i) {
    water.field(surface)[i] = n[i] < 0.97 * c.n0 ? 1 : 0;
    n_surface += static_cast<std::size_t>(water.field(surface)[i]);
  }

  // Hydrostatic pressure p = rho g (H - y): its gradient is (0, -rho g) everywhere.
  auto& p = water.field(p_field);
  for (std::size_t i = 0; i < water.size(); ++i) p[i] = rho * g * (height - water.positions()[i][1]);
  KhayyerGotohCorrection<2> kg;
  kg.update<KoshizukaWeight>(water.positions(), list, c);
  gradient<KoshizukaWeight>(water.positions(), list, p, c, kg, water.field(grad_kg));
  gradient<KoshizukaWeight>(water.positions(), list, p, c, NoGradientCorrection<2>{}, water.field(grad_std));
  std::vector<double> lap;
  laplacian<KoshizukaWeight>(water.positions(), list, p, c_lap, lap);

  // Errors over particles with a full neighbourhood (more than re_lap from every side).
  const Vec<2> exact(0, -rho * g);
  double err_kg = 0, err_std = 0, err_lap = 0;
  std::size_t interior = 0, interior_flagged = 0;
  for (std::size_t i = 0; i < water.size(); ++i) {
    const Vec<2>& x = water.positions()[i];
    if (x[0] < re_lap || x[0] > width - re_lap || x[1] < re_lap || x[1] > height - re_lap) continue;
    ++interior;
    interior_flagged += static_cast<std::size_t>(water.field(surface)[i]);
    err_kg = std::max(err_kg, (water.field(grad_kg)[i] - exact).norm() / exact.norm());
    err_std = std::max(err_std, (water.field(grad_std)[i] - exact).norm() / exact.norm());
    err_lap = std::max(err_lap, std::abs(lap[i]) / (rho * g / opt.l0));
  }

  std::printf("mpsfsi %s neighbour-search and operator demo (2D water column %.2f x %.2f m)\n",
              version_string, width, height);
  std::printf("  particles           %zu (l0 = %g m, jitter %.2f l0), %d thread(s)\n", water.size(), opt.l0,
              opt.jitter, parallel::max_threads());
  std::printf("  neighbour pairs     %zu (radius %.1f l0); first build: cell list %.2f ms, kd-tree %.2f ms; lists %s\n",
              list.num_pairs(), re_lap / opt.l0, 1e3 * t_cells, 1e3 * t_tree,
              list.num_pairs() == tree_list.num_pairs() ? "agree" : "DIFFER");
  std::printf("  n0 (re = 2.1 l0)    %.6f; free-surface particles (n < 0.97 n0): %zu,\n", c.n0, n_surface);
  std::printf("                      of which %zu deep inside: the jitter alone moves n by a few %%,\n"
              "                      which is why the number-density test needs a better detector\n",
              interior_flagged);
  std::printf("  grad p, %zu interior particles, max relative error:\n", interior);
  std::printf("    standard MPS       %.3e\n", err_std);
  std::printf("    Khayyer-Gotoh      %.3e\n", err_kg);
  std::printf("  lap p (exact 0)     max |lap p| l0 / (rho g) = %.3e\n", err_lap);

  mpsfsi_examples::make_output_folder(opt.out);
  cli.write_case(opt.out);
  const std::string vtu = numbered_file_name("water", 0);
  write_vtu(opt.out + "/" + vtu, water);
  PvdWriter pvd(opt.out + "/water.pvd");
  pvd.add(0.0, vtu);
  CsvWriter csv(opt.out + "/operator_errors.csv",
                {"l0", "jitter", "particles", "grad_error_standard", "grad_error_corrected", "lap_error"});
  csv.row({opt.l0, opt.jitter, static_cast<double>(water.size()), err_std, err_kg, err_lap});
  std::printf("  wrote %s/water.pvd (open in ParaView) and %s/operator_errors.csv\n", opt.out.c_str(),
              opt.out.c_str());
  return list.num_pairs() == tree_list.num_pairs() ? 0 : 1;
} catch (const mpsfsi::Error& e) {
  std::fprintf(stderr, "neighbor_demo: %s\n", e.what());
  return 1;
}
