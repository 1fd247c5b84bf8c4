// SPDX-License-Identifier: BSD-3-Clause
// Dam break (Martin & Moyce 1952; Koshizuka & Oka 1996): a water column a wide and 2a high
// collapses in a tank 4a long. Writes VTU/PVD snapshots, a CSV of the surge front and the
// residual column height, and prints them against the experiment's scaling.
//
//   dam_break [--dim 2|3] [--l0 m] [--dt s, 0 = automatic] [--end s] [--every s] [--out dir]
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>

#include <mpsfsi/fluid/fluid_solver.hpp>
#include <mpsfsi/io/csv_writer.hpp>
#include <mpsfsi/io/progress.hpp>
#include <mpsfsi/io/pvd_writer.hpp>
#include <mpsfsi/io/vtu_writer.hpp>
#include <mpsfsi/scenes/dam_break.hpp>

using namespace mpsfsi;

namespace {

struct Options {
  int dim = 2;
  double l0 = 0;      // default: 5 mm in 2D, 20 mm in 3D
  double dt = -1;     // default: 2e-4 s in 2D (issue 3's case), automatic in 3D; 0 = automatic
  double end = 0.4;   // s
  double every = 0.02;  // s between snapshots
  std::string out = "out/dam_break";
};

Options parse(int argc, char** argv) {
  Options o;
  for (int a = 1; a < argc; ++a) {
    const std::string key = argv[a];
    if (key == "--help" || a + 1 >= argc) {
      std::fprintf(stderr, "usage: dam_break [--dim 2|3] [--l0 m] [--dt s] [--end s] [--every s] [--out dir]\n");
      std::exit(key == "--help" ? 0 : 2);
    }
    const std::string v = argv[++a];
    if (key == "--dim") o.dim = std::stoi(v);
    else if (key == "--l0") o.l0 = std::stod(v);
    else if (key == "--dt") o.dt = std::stod(v);
    else if (key == "--end") o.end = std::stod(v);
    else if (key == "--every") o.every = std::stod(v);
    else if (key == "--out") o.out = v;
    else {
      std::fprintf(stderr, "dam_break: unknown option %s\n", key.c_str());
      std::exit(2);
    }
  }
  if (o.dim != 2 && o.dim != 3) {
    std::fprintf(stderr, "dam_break: --dim must be 2 or 3\n");
    std::exit(2);
  }
  if (o.l0 <= 0) o.l0 = o.dim == 2 ? 0.005 : 0.02;
  if (o.dt < 0) o.dt = o.dim == 2 ? 2e-4 : 0.0;
  return o;
}

template <int Dim>
int run(const Options& o) {
  const double a = 0.25, g = 9.81;  // column width (m); height 2a; tank 4a x 0.6 m
  FluidParameters<Dim> p;
  p.l0 = o.l0;
  p.dt = o.dt;
  FluidSolver<Dim> solver(scenes::dam_break<Dim>(a, 2 * a, 4 * a, 0.6, o.l0, Dim == 3 ? 0.1 : 0.0), p);
  std::filesystem::create_directories(o.out);
  PvdWriter pvd(o.out + "/dam_break.pvd");
  CsvWriter csv(o.out + "/dam_break.csv", {"t", "T", "Z_over_a", "tau", "H_over_2a", "ppe_iterations", "wall_s"});
  ProgressReporter progress(o.end);
  std::size_t frame = 0;
  double next_output = 0, wall = 0;
  std::printf("dam break %dD: %zu particles, l0 = %g m, dt = %s, to t = %g s\n", Dim, solver.particles().size(), o.l0,
              o.dt > 0 ? (std::to_string(o.dt) + " s").c_str() : "automatic (Courant 0.2)", o.end);
  std::printf("%8s %8s %8s %8s %8s\n", "t (s)", "T", "Z/a", "tau", "H/2a");
  for (;;) {
    const double t = solver.time();
    if (t >= next_output - 1e-12) {
      const std::string file = numbered_file_name("dam_break", frame++);
      write_vtu(o.out + "/" + file, solver.particles());
      pvd.add(t, file);
      const double z = scenes::surge_front(solver.particles(), o.l0) / a;
      const double h = scenes::column_height(solver.particles(), o.l0) / (2 * a);
      csv.row({t, t * std::sqrt(2 * g / a), z, t * std::sqrt(g / a), h,
               static_cast<double>(solver.last_solve().iterations), wall});
      std::printf("%8.4f %8.3f %8.3f %8.3f %8.3f\n", t, t * std::sqrt(2 * g / a), z, t * std::sqrt(g / a), h);
      next_output += o.every;
    }
    if (t >= o.end - 1e-12) break;
    solver.step();
    wall += solver.last_timings().total();
    progress.update(solver.step_count(), solver.time());
  }
  progress.finish();
  std::printf("wrote %s/dam_break.pvd and %s/dam_break.csv; plot with /usr/bin/python3 examples/dam_break/plot.py %s\n", o.out.c_str(),
              o.out.c_str(), o.out.c_str());
  return 0;
}

}  // namespace

int main(int argc, char** argv) try {
  const Options o = parse(argc, argv);
  return o.dim == 2 ? run<2>(o) : run<3>(o);
} catch (const mpsfsi::SimulationError& e) {
  std::fprintf(stderr, "dam_break: %s\n(the last good snapshot is the last one in the .pvd)\n", e.what());
  return 1;
} catch (const mpsfsi::Error& e) {
  std::fprintf(stderr, "dam_break: %s\n", e.what());
  return 1;
}
