// SPDX-License-Identifier: BSD-3-Clause
// Three-point bending of ice beams with brittle fracture: the five cases of the paper's Table 1
// (physics-notes section 6). E and sigma_f from Table 1 are the inputs; the simulated flexural
// strain 6 h dd / L^2 at the peak load is compared with the experiment's. Writes, per case, a CSV
// of load, deflection and the horizontal stress at the top and bottom of mid-span against time
// (the paper's Fig 6), the final particles with damage (crack path, Fig 5), VTU/PVD snapshots,
// and a summary CSV; plot.py renders the PNGs (Figs 5-7).
//
//   three_point_bending [--case all|02|03|04|05|10] [--dim 2|3] [--l0 m] [--speed m/s]
//                       [--plane stress|strain] [--point-stress] [--centre-stress] [--out dir] [--no-output]
#include <cstdio>
#include <cstdlib>
#include <string>

#include "bending_test.hpp"

namespace {

struct Options {
  std::string which = "all";
  int dim = 2;
  bending::Options run;
};

Options parse(int argc, char** argv) {
  Options o;
  o.run.out = "out/three_point_bending";
  for (int a = 1; a < argc; ++a) {
    const std::string key = argv[a];
    if (key == "--no-output") {
      o.run.out.clear();
      continue;
    }
    if (key == "--point-stress") {  // the criterion reads each particle's own stress
      o.run.average_failure_stress = false;
      continue;
    }
    if (key == "--centre-stress") {  // the criterion reads the stress at particle centres
      o.run.failure_stress_at_surface = false;
      continue;
    }
    if (key == "--help" || a + 1 >= argc) {
      std::fprintf(stderr,
                   "usage: three_point_bending [--case all|02|03|04|05|10] [--dim 2|3] [--l0 m] [--speed m/s] "
                   "[--plane stress|strain] [--point-stress] [--centre-stress] [--out dir] [--no-output]\n");
      std::exit(key == "--help" ? 0 : 2);
    }
    const std::string v = argv[++a];
    if (key == "--case") o.which = v;
    else if (key == "--dim") o.dim = std::stoi(v);
    else if (key == "--l0") o.run.l0 = std::stod(v);
    else if (key == "--speed") o.run.speed = std::stod(v);
    else if (key == "--plane") o.run.plane_model = v == "strain" ? mpsfsi::PlaneModel::plane_strain : mpsfsi::PlaneModel::plane_stress;
    else if (key == "--out") o.run.out = v;
    else if (key == "--contact-damping") o.run.contact_damping = std::stod(v);
    else {
      std::fprintf(stderr, "three_point_bending: unknown option %s\n", key.c_str());
      std::exit(2);
    }
  }
  if (o.dim != 2 && o.dim != 3) {
    std::fprintf(stderr, "three_point_bending: --dim must be 2 or 3\n");
    std::exit(2);
  }
  return o;
}

}  // namespace

int main(int argc, char** argv) try {
  Options o = parse(argc, argv);
  o.run.progress = o.dim == 3;
  std::printf("Three-point bending of ice beams (Table 1), %dD %s, l0 = %g m, indenter %g m/s, span 0.18 m\n", o.dim,
              o.dim == 3 ? "" : (o.run.plane_model == mpsfsi::PlaneModel::plane_stress ? "plane stress" : "plane strain"),
              o.run.l0, o.run.speed);
  std::printf("%4s %7s %7s %8s %8s | %9s %10s %9s %9s %8s | %6s %5s %7s %6s\n", "case", "E MPa", "sf MPa", "Pexp N",
              "ddexp mm", "Psim N", "dd@P mm", "eps_sim", "eps_exp", "error", "broken", "crack", "surface", "wall s");
  std::unique_ptr<mpsfsi::CsvWriter> summary;
  if (!o.run.out.empty()) {
    std::filesystem::create_directories(o.run.out);
    summary = std::make_unique<mpsfsi::CsvWriter>(
        o.run.out + "/summary.csv",
        std::vector<std::string>{"case", "E_Pa", "sigma_f_Pa", "P_exp_N", "dd_exp_m", "P_sim_N", "dd_sim_m",
                                 "bottom_dd_sim_m", "indenter_at_peak_m", "eps_sim", "eps_exp", "error", "broken", "crack_offset_m",
                                 "fracture_surface_offset_m", "wall_s"});
  }
  double total = 0, worst = 0;
  for (const auto& c : bending::table1()) {
    if (o.which != "all" && o.which != c.name) continue;
    const auto r = o.dim == 2 ? bending::run<2>(c, o.run) : bending::run<3>(c, o.run);
    total += r.wall_seconds;
    worst = std::max(worst, std::abs(r.error()));
    char surface[16] = "-";
    if (r.broken) std::snprintf(surface, sizeof surface, "%.1fl0", r.fracture_surface_offset / r.l0);
    std::printf("%4s %7.2f %7.3f %8.1f %8.3f | %9.1f %10.4f %9.5f %9.5f %+7.2f%% | %6s %3.1fl0 %7s %6.1f\n", c.name.c_str(),
                c.youngs_modulus() / 1e6, c.tensile_strength() / 1e6, c.peak_load, 1e3 * c.deflection, r.peak_load,
                1e3 * r.deflection_at_peak, r.flexural_strain, c.flexural_strain(), 100 * r.error(), r.broken ? "yes" : "NO",
                r.crack_offset / r.l0, surface, r.wall_seconds);
    if (r.broken)
      std::printf("     fracture surface: %zu crossings of %zu rows along x, %zu of them more than 2 l0 from the centre line\n",
                  r.fracture_surface_crossings, r.lattice_rows, r.fracture_surface_beyond_2l0);
    if (r.first_failure >= 0)
      std::printf("     energy after the first crack (indenter work counted): at most %+.2f %% of the %.4g J%s at the crack\n",
                  100 * r.energy_rise_after_failure, r.energy_at_failure, o.dim == 2 ? "/m" : "");
    if (!r.broken)
      std::printf("     not in two pieces: %zu intact bonds stretched over 5 %%; without them the beam %s\n",
                  r.overstretched_bonds, r.broken_but_overstretched ? "is in two pieces" : "is still one piece");
    if (summary)
      summary->row({std::stod(c.name), c.youngs_modulus(), c.tensile_strength(), c.peak_load, c.deflection, r.peak_load,
                    r.deflection_at_peak, r.bottom_deflection_at_peak, r.indenter_at_peak, r.flexural_strain, c.flexural_strain(), r.error(),
                    r.broken ? 1.0 : 0.0, r.crack_offset, r.fracture_surface_offset, r.wall_seconds});
  }
  std::printf("largest |error| %.2f %%, total wall time %.1f s on %d threads\n", 100 * worst, total,
              mpsfsi::parallel::max_threads());
  if (!o.run.out.empty())
    std::printf("wrote %s; plot with /usr/bin/python3 examples/three_point_bending/plot.py %s\n", o.run.out.c_str(),
                o.run.out.c_str());
  return 0;
} catch (const mpsfsi::SimulationError& e) {
  std::fprintf(stderr, "three_point_bending: %s\n", e.what());
  return 1;
} catch (const mpsfsi::Error& e) {
  std::fprintf(stderr, "three_point_bending: %s\n", e.what());
  return 1;
}
