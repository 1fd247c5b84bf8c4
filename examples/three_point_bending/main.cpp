// SPDX-License-Identifier: BSD-3-Clause
// Three-point bending of ice beams with brittle fracture: the five cases of the paper's Table 1
// (docs/theory.md, section 6). sigma_f and E from Table 1 are the inputs, E as the material modulus
// (default) or as Table 1's apparent one (docs/theory.md, section 6.3); the simulated flexural
// strain 6 h dd / L^2 at the peak load is compared with the experiment's. Writes, per case, a CSV
// of load, deflection and the horizontal stress at the top and bottom of mid-span against time
// (the paper's Fig 6), the final particles with damage (crack path, Fig 5), VTU/PVD snapshots,
// and a summary CSV; plot.py renders the PNGs (Figs 5-7). `three_point_bending --help` lists the
// options.
#include <cstdio>
#include <cstdlib>
#include <string>

#include "bending_test.hpp"
#include "common/case_options.hpp"
#include "common/output_folder.hpp"

namespace {

struct Options {
  std::string which = "all";
  int dim = 2;
  std::string plane = "stress";
  std::string modulus = "material";
  std::string crack_side = "slab";
  bool point_stress = false, centre_stress = false, no_output = false;
  bending::Options run;
};

}  // namespace

int main(int argc, char** argv) try {
  Options o;
  o.run.out = "out/three_point_bending";
  mpsfsi_examples::CaseOptions cli("three_point_bending",
                                   "Three-point bending of the ice beams of the paper's Table 1, with brittle fracture");
  using mpsfsi_examples::one_of;
  using mpsfsi_examples::positive;
  cli.add("--case", o.which, "which case of Table 1")->check(one_of({"all", "02", "03", "04", "05", "10"}));
  cli.add("--dim", o.dim, "dimension")->check(one_of({"2", "3"}));
  cli.add("--modulus", o.modulus,
          "E given to the solid: the material modulus a Timoshenko beam needs to deflect as the specimen did, or "
          "Table 1's apparent (Euler-Bernoulli) modulus as in the paper")
      ->check(one_of({"material", "apparent"}));
  cli.add("--l0", o.run.l0, "target particle spacing (the beam height is made a whole number of spacings)", "m")
      ->check(positive());
  cli.add("--speed", o.run.speed, "indenter speed, reached after a smooth ramp", "m/s")->check(positive());
  cli.add("--plane", o.plane, "2D plane model")->check(one_of({"stress", "strain"}));
  cli.flag("--point-stress", o.point_stress, "the criterion reads each particle's own stress (not averaged over its bonds)");
  cli.flag("--centre-stress", o.centre_stress, "the criterion reads the stress at particle centres (not at the surface)");
  cli.add("--crack-side", o.crack_side,
          "how a failing particle's crack plane divides its bonds: the particle loses both sides of its slab and "
          "becomes the crack, keeps its side towards +x, or keeps the side that holds it more firmly")
      ->check(one_of({"slab", "fixed-sign", "attachment"}));
  cli.add("--contact-damping", o.run.contact_damping, "damping ratio of the contact's normal dashpot")
      ->check(mpsfsi_examples::non_negative());
  cli.add("--out", o.run.out, "output folder");
  cli.flag("--no-output", o.no_output, "write no files");
  cli.add("--checkpoint-every", o.run.checkpoint_every,
          "simulated time between checkpoints (out/checkpoint_case<case>_<step>.bin); 0: only on Ctrl-C / SIGTERM", "s")
      ->check(mpsfsi_examples::non_negative());
  cli.add("--restart", o.run.restart, "checkpoint to continue from, with --case naming its case (same options otherwise)");
  if (const auto code = cli.parse_or_exit_code(argc, argv)) return *code;
  if (!o.run.restart.empty() && o.which == "all") {
    std::fprintf(stderr, "three_point_bending: --restart needs --case (the case the checkpoint belongs to)\n");
    return 2;
  }
  if (cli.print_case_if_requested()) return 0;
  o.run.modulus = o.modulus == "apparent" ? bending::Modulus::apparent : bending::Modulus::material;
  o.run.plane_model = o.plane == "strain" ? mpsfsi::PlaneModel::plane_strain : mpsfsi::PlaneModel::plane_stress;
  o.run.average_failure_stress = !o.point_stress;
  o.run.failure_stress_at_surface = !o.centre_stress;
  o.run.crack_side = o.crack_side == "attachment"   ? mpsfsi::CrackSide::attachment
                     : o.crack_side == "fixed-sign" ? mpsfsi::CrackSide::fixed_sign
                                                    : mpsfsi::CrackSide::slab;
  const std::string out = o.no_output ? std::string() : o.run.out;
  o.run.out = out;
  o.run.progress = true;
  o.run.checkpoints = !out.empty();

  if (!out.empty()) mpsfsi_examples::make_output_folder(out);  // before anything is printed
  std::printf("Three-point bending of ice beams (Table 1), %dD %s, l0 = %g m, indenter %g m/s, span 0.18 m, %s modulus\n",
              o.dim, o.dim == 3 ? "" : (o.run.plane_model == mpsfsi::PlaneModel::plane_stress ? "plane stress" : "plane strain"),
              o.run.l0, o.run.speed, o.modulus.c_str());
  std::fprintf(stderr, "%s; the end time is 1.6 x the time at which the beam would reach Table 1's deflection\n",
               mpsfsi::ProgressReporter::legend());
  std::printf("%4s %7s %7s %8s %8s | %9s %10s %9s %9s %8s | %6s %5s %7s %6s\n", "case", "E MPa", "sf MPa", "Pexp N",
              "ddexp mm", "Psim N", "dd@P mm", "eps_sim", "eps_exp", "error", "broken", "crack", "surface", "wall s");
  std::unique_ptr<mpsfsi::CsvWriter> summary;
  if (!out.empty()) {
    cli.write_case(out);
    summary = std::make_unique<mpsfsi::CsvWriter>(
        out + "/summary.csv",
        std::vector<std::string>{"case", "E_Pa", "E_input_Pa", "sigma_f_Pa", "P_exp_N", "dd_exp_m", "P_sim_N", "dd_sim_m",
                                 "bottom_dd_sim_m", "indenter_at_peak_m", "eps_sim", "eps_exp", "error", "broken", "crack_offset_m",
                                 "fracture_surface_offset_m", "wall_s"});
  }
  double total = 0, worst = 0;
  for (const auto& c : bending::table1()) {
    if (o.which != "all" && o.which != c.name) continue;
    const auto r = o.dim == 2 ? bending::run<2>(c, o.run) : bending::run<3>(c, o.run);
    if (r.stop_code) return r.stop_code;
    total += r.wall_seconds;
    worst = std::max(worst, std::abs(r.error()));
    char surface[16] = "-";
    if (r.broken) std::snprintf(surface, sizeof surface, "%.1fl0", r.fracture_surface_offset / r.l0);
    std::printf("%4s %7.2f %7.3f %8.1f %8.3f | %9.1f %10.4f %9.5f %9.5f %+7.2f%% | %6s %3.1fl0 %7s %6.1f\n", c.name.c_str(),
                r.youngs_modulus / 1e6, c.tensile_strength() / 1e6, c.peak_load, 1e3 * c.deflection, r.peak_load,
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
    std::fflush(stdout);
    if (summary)
      summary->row({std::stod(c.name), c.youngs_modulus(), r.youngs_modulus, c.tensile_strength(), c.peak_load, c.deflection, r.peak_load,
                    r.deflection_at_peak, r.bottom_deflection_at_peak, r.indenter_at_peak, r.flexural_strain, c.flexural_strain(), r.error(),
                    r.broken ? 1.0 : 0.0, r.crack_offset, r.fracture_surface_offset, r.wall_seconds});
  }
  std::printf("largest |error| %.2f %%, total wall time %.1f s on %d threads\n", 100 * worst, total,
              mpsfsi::parallel::max_threads());
  if (!out.empty())
    std::printf("wrote %s (case.yaml reruns this case); plot with python3 examples/three_point_bending/plot.py %s\n",
                out.c_str(), out.c_str());
  return 0;
} catch (const mpsfsi::SimulationError& e) {
  std::fprintf(stderr, "three_point_bending: %s\n", e.what());
  return 1;
} catch (const mpsfsi::Error& e) {
  std::fprintf(stderr, "three_point_bending: %s\n", e.what());
  return 1;
}
