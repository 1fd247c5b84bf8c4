// SPDX-License-Identifier: BSD-3-Clause
// Oscillating clamped plate (Gray, Monaghan & Swift 2001): a plate L = 0.2 m, H = 0.02 m,
// E = 2 MPa, nu = 0.3975, rho = 1000 kg/m3 sticks out of a clamp and starts with the first-mode
// velocity profile (tip speed 0.01 c0). Writes VTU/PVD snapshots, a CSV of the tip displacement
// and the energies, and prints the measured period against the analytic 0.254 s (plane strain).
// `oscillating_plate --help` lists the options.
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include <mpsfsi/io/csv_writer.hpp>
#include <mpsfsi/io/progress.hpp>
#include <mpsfsi/io/pvd_writer.hpp>
#include <mpsfsi/io/vtu_writer.hpp>
#include <mpsfsi/scenes/oscillating_plate.hpp>
#include <mpsfsi/solid/elastic_solver.hpp>

#include "common/case_options.hpp"
#include "common/output_folder.hpp"

using namespace mpsfsi;

namespace {

struct Options {
  int dim = 2;
  int layers = 10;       // particles across the thickness
  double periods = 3;    // simulated time in analytic periods
  double every = 0.01;   // s between snapshots
  std::string model = "corrected";
  std::string out = "out/oscillating_plate";
};

template <int Dim, class Policies>
int run(const Options& o) {
  scenes::OscillatingPlate plate;
  const double l0 = plate.thickness / o.layers;
  std::vector<std::size_t> clamped;
  std::size_t tip = 0;
  SolidParameters<Dim> p;
  p.l0 = l0;
  plate.set_material(p);
  p.plane_model = PlaneModel::plane_strain;
  ElasticSolver<Dim, Policies> solver(plate.particles<Dim>(l0, 4, clamped, tip), p);
  for (const auto i : clamped) solver.clamp(i);
  const double period = plate.period(Dim == 2), end = o.periods * period;
  mpsfsi_examples::make_output_folder(o.out);
  PvdWriter pvd(o.out + "/oscillating_plate.pvd");
  CsvWriter csv(o.out + "/oscillating_plate.csv", {"t", "tip_dy", "kinetic", "strain", "total"});
  ProgressReporter progress(end);
  std::printf("oscillating plate %dD (%s model): %zu particles, H/l0 = %d, dt = %.3g s, analytic T = %.5f s%s\n", Dim,
              Policies::stress_model::name, solver.particles().size(), o.layers, solver.dt(), period,
              Dim == 2 ? " (plane strain)" : " (3D bar)");
  std::fprintf(stderr, "%s\n", ProgressReporter::legend());
  const double y0 = solver.particles().positions()[tip][1];
  std::vector<double> crossings;
  double previous = 0, next_output = 0;
  const long long energy_every = std::max(1LL, static_cast<long long>(period / 200 / solver.dt()));
  std::size_t frame = 0;
  for (;;) {
    const double t = solver.time(), y = solver.particles().positions()[tip][1] - y0;
    if (solver.step_count() > 0 && (previous < 0) != (y < 0)) crossings.push_back(t - solver.last_dt() * y / (y - previous));
    previous = y;
    if (t >= next_output - 1e-12) {
      const std::string file = numbered_file_name("oscillating_plate", frame++);
      write_vtu(o.out + "/" + file, solver.output());
      pvd.add(t, file);
      next_output += o.every;
    }
    if (solver.step_count() % energy_every == 0) {
      const double kinetic = solver.kinetic_energy(), strain = solver.strain_energy();
      csv.row({t, y, kinetic, strain, kinetic + strain});
    }
    if (t >= end - 1e-12) break;
    solver.step();
    progress.update(solver.step_count(), solver.time());
  }
  progress.finish();
  if (crossings.size() >= 2) {
    const double measured = 2 * (crossings.back() - crossings.front()) / static_cast<double>(crossings.size() - 1);
    std::printf("period %.5f s against %.5f s: %+.2f %%\n", measured, period, 100 * (measured / period - 1));
  }
  std::printf("wrote %s/oscillating_plate.pvd and .csv; plot with python3 examples/oscillating_plate/plot.py %s\n",
              o.out.c_str(), o.out.c_str());
  return 0;
}

}  // namespace

int main(int argc, char** argv) try {
  Options o;
  mpsfsi_examples::CaseOptions cli("oscillating_plate",
                                   "Oscillating clamped plate in its first mode (Gray, Monaghan & Swift 2001)");
  cli.add("--dim", o.dim, "dimension (3: a bar of square section)")->check(mpsfsi_examples::one_of({"2", "3"}));
  cli.add("--layers", o.layers, "particles across the thickness H (H/l0), at least 2")
      ->check(CLI::Range(2, 1000));
  cli.add("--periods", o.periods, "simulated time in analytic periods")->check(mpsfsi_examples::positive());
  cli.add("--every", o.every, "interval between snapshots", "s")->check(mpsfsi_examples::positive());
  cli.add("--model", o.model, "stress model: corrected total Lagrangian or the paper's eqs 16-17")
      ->check(mpsfsi_examples::one_of({"corrected", "paper"}));
  cli.add("--out", o.out, "output folder");
  if (const auto code = cli.parse_or_exit_code(argc, argv)) return *code;
  if (cli.print_case_if_requested()) return 0;
  mpsfsi_examples::make_output_folder(o.out);
  cli.write_case(o.out);
  if (o.dim == 2) return o.model == "paper" ? run<2, PaperSolidPolicies<2>>(o) : run<2, SolidDefaults<2>>(o);
  return o.model == "paper" ? run<3, PaperSolidPolicies<3>>(o) : run<3, SolidDefaults<3>>(o);
} catch (const mpsfsi::SimulationError& e) {
  std::fprintf(stderr, "oscillating_plate: %s\n(the last good snapshot is the last one in the .pvd)\n", e.what());
  return 1;
} catch (const mpsfsi::Error& e) {
  std::fprintf(stderr, "oscillating_plate: %s\n", e.what());
  return 1;
}
