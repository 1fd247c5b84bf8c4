// SPDX-License-Identifier: BSD-3-Clause
// The paper's application (its Figs 10-14, docs/theory.md section 7): a square water droplet
// 0.1 m x 0.1 m falls at 9 m/s onto the free end of an ice cantilever 0.5 m x 0.05 m clamped at
// its left end; ice as Table 1 case 02 (E = 270.084 MPa, nu = 0.3, sigma_f = 1.140 MPa,
// 917 kg/m3). Runs without and with brittle fracture. Writes, per run, VTU/PVD of fluid and
// beam every millisecond, particle CSVs of the snapshots from t = 4 ms to 10 ms (plot.py renders
// them as in Fig 11), the beam tip's displacement against time, and every particle failure
// (the crack paths). With --dim 3 the 2D section is extruded along z over --width: beam and
// droplet span the width, y is up. `droplet_on_ice_beam --help` lists the options.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include <mpsfsi/fluid/fluid_solver.hpp>
#include <mpsfsi/fracture/failure_criteria.hpp>
#include <mpsfsi/fracture/fracture_process.hpp>
#include <mpsfsi/fsi/fsi_coupler.hpp>
#include <mpsfsi/io/checkpoint.hpp>
#include <mpsfsi/io/csv_writer.hpp>
#include <mpsfsi/io/progress.hpp>
#include <mpsfsi/io/pvd_writer.hpp>
#include <mpsfsi/io/vtu_writer.hpp>
#include <mpsfsi/scenes/solid_block.hpp>
#include <mpsfsi/solid/elastic_solver.hpp>

#include "common/case_options.hpp"
#include "common/output_folder.hpp"
#include "common/output_record.hpp"
#include "common/run_checkpoints.hpp"
#include "three_point_bending/bending_test.hpp"

using namespace mpsfsi;

namespace {

struct Options {
  int dim = 2;
  double l0 = 0;        // 0: 2.5 mm in 2D (the paper's), 5 mm in 3D
  double width = 0.1;   // 3D: extent along z of beam and droplet, two beam thicknesses
  double dt = 0;        // fluid step: automatic (Courant 0.2); the paper used a fixed 1e-5 s
  double end = 0.010;   // s
  double gap = 0.005;   // droplet bottom above the beam (the paper does not print it)
  double speed = 9.0;   // m/s, downwards
  std::string scheme = "explicit";
  std::string only;     // "with" or "without": one run only
  std::string plane = "stress";
  // Where the criterion reads the stress (SolidParameters::failure_stress_at_surface); the
  // default is the library's.
  std::string failure_stress = "surface";
  std::string crack_side = "slab";  // SolidParameters::crack_side; the default is the library's
  double solid_courant = 0;     // structure step as a fraction of l0 / c; 0: the library's default
  double checkpoint_every = 0;  // s between checkpoints; 0: only on Ctrl-C / SIGTERM
  std::string restart;          // checkpoint to continue from (with --only)
  std::string out = "out/droplet_on_ice_beam";
};

// What the output loop has done so far (csv_rows: tip.csv), and the largest |tip dy| so far.
struct OutputState : mpsfsi_examples::OutputRecord {
  double max_tip = 0;

  template <class Archive>
  void checkpoint_state(Archive& a) {
    OutputRecord::checkpoint_state(a);
    a.value(max_tip);
  }
};

constexpr double beam_length = 0.5, beam_height = 0.05, droplet_size = 0.1;
constexpr int clamp_columns = 3;

struct RunSummary {
  double wall = 0, fluid = 0, solid = 0;
  std::size_t cut = 0, failures = 0;
  double first_failure = -1, max_tip = 0;
  int stop_code = 0;  // 128 + signal when stopped by Ctrl-C / SIGTERM
};

// CSV column names with the coordinates (x, y and, in 3D, z, each followed by `suffix`) between
// `before` and `after`, and a row of the same shape.
template <int Dim>
std::vector<std::string> with_coordinates(const std::vector<std::string>& before, const std::vector<std::string>& after,
                                          const std::string& suffix = "") {
  std::vector<std::string> names = before;
  for (int k = 0; k < Dim; ++k) names.push_back(std::string(1, "xyz"[k]) + suffix);
  names.insert(names.end(), after.begin(), after.end());
  return names;
}
template <int Dim>
std::vector<double> row_with(std::vector<double> before, const Vec<Dim>& x, const std::vector<double>& after) {
  for (int k = 0; k < Dim; ++k) before.push_back(x[k]);
  before.insert(before.end(), after.begin(), after.end());
  return before;
}

// Beam particles x, y (z), sigma_xx, max principal stress, damage (one row each) at a snapshot;
// in 3D also z0, the reference z, by which plot.py picks the mid-width layer.
template <int Dim, class Solid>
void write_beam_snapshot(const std::string& path, Solid& beam) {
  std::vector<std::string> after = {"sxx_Pa", "sigma1_Pa", "damage"};
  if (Dim == 3) after.push_back("z0");
  CsvWriter csv(path, with_coordinates<Dim>({}, after));
  const auto& out = beam.output();
  const auto& stress = beam.stresses();
  const auto& x = out.positions();
  for (std::size_t i = 0; i < x.size(); ++i) {
    Vec<Dim> direction;
    const double sigma1 = MaxPrincipalStress::principal<Dim, double>(stress[i], direction);
    std::vector<double> values = {stress[i](0, 0), sigma1, beam.bonds().damage(i)};
    if (Dim == 3) values.push_back(beam.reference_positions()[i][Dim - 1]);
    csv.row(row_with<Dim>({}, x[i], values));
  }
}

// A box [lower, upper] in x and y; in 3D extruded over [0, width] along z.
template <int Dim>
ParticleSet<Dim> extruded_block(const Vec<2>& lower, const Vec<2>& upper, double width, double l0) {
  Vec<Dim> lo = Vec<Dim>::Zero(), hi = Vec<Dim>::Zero();
  lo.template head<2>() = lower;
  hi.template head<2>() = upper;
  if constexpr (Dim == 3) hi[2] = width;
  return scenes::material_block<Dim>(lo, hi, l0);
}

template <int Dim, class Policies, class Scheme>
RunSummary run(const Options& o, bool fracture, const std::string& dir) {
  const auto ice = bending::table1().front();  // case 02
  const double l0 = o.l0;
  // Beam [-clamp, L] x [0, h] (x [0, width]); the columns left of x = 0 are clamped.
  auto beam_set = extruded_block<Dim>(Vec<2>(-clamp_columns * l0, 0), Vec<2>(beam_length, beam_height), o.width, l0);
  SolidParameters<Dim> sp;
  sp.l0 = l0;
  sp.density = 917;
  sp.youngs_modulus = ice.youngs_modulus();
  sp.poisson_ratio = 0.3;
  if constexpr (Dim == 2) sp.plane_model = o.plane == "stress" ? PlaneModel::plane_stress : PlaneModel::plane_strain;
  if (o.solid_courant > 0) sp.courant = o.solid_courant;  // above max_courant: refused by validate()
  if (fracture) {
    sp.tensile_strength = ice.tensile_strength();
    sp.failure_stress_at_surface = o.failure_stress == "surface";
    sp.crack_side = o.crack_side == "fixed-sign"   ? CrackSide::fixed_sign
                    : o.crack_side == "attachment" ? CrackSide::attachment
                                                   : CrackSide::slab;
  }
  ElasticSolver<Dim, Policies> beam(beam_set, sp);
  for (auto i : scenes::select(beam_set, [](const Vec<Dim>& x) { return x[0] < 0; })) beam.clamp(i);
  // The tip: the particle nearest the middle of the free end's face.
  Vec<Dim> tip_point = Vec<Dim>::Zero();
  tip_point.template head<2>() = Vec<2>(beam_length, beam_height / 2);
  if constexpr (Dim == 3) tip_point[2] = o.width / 2;
  std::size_t tip = 0;
  double best = 1e300;
  for (std::size_t i = 0; i < beam_set.size(); ++i) {
    const double d = (beam_set.positions()[i] - tip_point).norm();
    if (d < best) best = d, tip = i;
  }
  // The droplet over the free end, falling at o.speed.
  auto droplet = extruded_block<Dim>(Vec<2>(beam_length - droplet_size, beam_height + o.gap),
                                     Vec<2>(beam_length, beam_height + o.gap + droplet_size), o.width, l0);
  Vec<Dim> down = Vec<Dim>::Zero();
  down[1] = -1;
  for (std::size_t i = 0; i < droplet.size(); ++i) {
    droplet.kinds()[i] = ParticleKind::fluid;
    droplet.velocities()[i] = o.speed * down;
  }
  FluidParameters<Dim> fp;
  fp.l0 = l0;
  fp.dt = o.dt;
  fp.gravity = 9.81 * down;  // y is up in 2D and 3D (the default is along the last axis)
  // The breaking beam can trap droplet particles between its fragments, out of reach of the
  // free surface: left out of the PPE with P = 0 (counted in the summary) instead of an error.
  if (fracture) fp.enclosed_region = EnclosedRegion::zero_pressure;
  FsiCoupler<FluidSolver<Dim>, ElasticSolver<Dim, Policies>, Scheme> c(std::move(droplet), fp, std::move(beam));

  mpsfsi_examples::make_output_folder(dir);
  const Vec<Dim> tip0 = c.solid().particles().positions()[tip];
  OutputState state;
  if (!o.restart.empty()) {
    read_checkpoint(o.restart, c, state);
    std::printf("continuing from %s: step %lld, t = %g s\n", o.restart.c_str(), c.step_count(), c.time());
  }
  PvdWriter fluid_pvd(dir + "/fluid.pvd"), beam_pvd(dir + "/beam.pvd");
  for (long long k = 0; k < state.frames; ++k) {
    const auto frame = static_cast<std::size_t>(k);
    fluid_pvd.add(state.frame_times[frame], numbered_file_name("fluid", frame));
    beam_pvd.add(state.frame_times[frame], numbered_file_name("beam", frame));
  }
  // With the energies of beam and droplet (per unit width in 2D). Their sum can rise only by the
  // droplet's fall under gravity (about 0.1 J per kg and cm); the fluid's viscosity, the collision
  // model and the bond viscosity dissipate.
  const std::vector<std::string> tip_columns = {"t",       "tip_dx",          "tip_dy",        "cut_bonds",
                                                "force_x", "force_y",         "beam_kinetic_J", "beam_strain_J",
                                                "fluid_kinetic_J"};
  CsvWriter tip_csv = o.restart.empty() ? CsvWriter(dir + "/tip.csv", tip_columns)
                                        : CsvWriter::continue_after(dir + "/tip.csv", tip_columns, state.csv_rows);
  mpsfsi_examples::RunCheckpoints checkpoints(dir, o.checkpoint_every);
  char model[64];
  if (Dim == 2) std::snprintf(model, sizeof model, "plane %s", o.plane.c_str());
  else std::snprintf(model, sizeof model, "3D, width %g m", o.width);
  std::printf("\n== %s fracture (%s coupling, %s): %zu droplet + %zu beam particles, l0 = %g m, dt_f = %g s, "
              "dt_s = %.3g s, bond viscosity %g\n",
              fracture ? "with" : "without", Scheme::name, model, c.structure_offset(),
              c.solid().particles().size(), l0, o.dt, c.solid().dt(), c.solid().parameters().bond_viscosity);
  std::printf("%8s %11s %11s %9s %9s\n", "t (ms)", "tip dy (mm)", "tip dx (mm)", "cut bonds", "failures");
  ProgressReporter progress(o.end);
  const auto t0 = std::chrono::steady_clock::now();
  RunSummary s;
  const double every = 1e-3;
  for (;;) {
    const double t = c.time();
    // Checkpoints at the top of the loop: a restarted run writes this time's outputs again.
    if (checkpoints.due(t) || checkpoints.stop_requested()) {
      state.csv_rows = tip_csv.rows();
      const std::string path = checkpoints.write(c, c.step_count(), t, state);
      std::fprintf(stderr, "checkpoint: %s (t = %g s)\n", path.c_str(), t);
      if (checkpoints.stop_requested()) {
        std::fprintf(stderr, "droplet_on_ice_beam: stopped by a signal; continue with --only %s --restart %s\n",
                     fracture ? "with" : "without", path.c_str());
        s.stop_code = checkpoints.stop_exit_code();
        return s;
      }
    }
    const Vec<Dim> d = c.solid().particles().positions()[tip] - tip0;
    state.max_tip = std::max(state.max_tip, std::abs(d[1]));
    double fluid_kinetic = 0;
    const auto& fluid = c.fluid().particles();
    for (std::size_t i = 0; i < c.structure_offset(); ++i)
      fluid_kinetic += 0.5 * c.fluid().parameters().density * std::pow(l0, Dim) * fluid.velocities()[i].squaredNorm();
    tip_csv.row({t, d[0], d[1], static_cast<double>(c.solid().cut_bonds()), c.total_interface_force()[0],
                 c.total_interface_force()[1], c.solid().kinetic_energy(), c.solid().strain_energy(), fluid_kinetic});
    if (t >= state.next_output - 1e-9) {
      const auto frame = static_cast<std::size_t>(state.frames);
      const std::string ff = numbered_file_name("fluid", frame), bf = numbered_file_name("beam", frame);
      write_vtu(dir + "/" + ff, c.fluid().particles());
      write_vtu(dir + "/" + bf, c.solid().output());
      fluid_pvd.add(t, ff);
      beam_pvd.add(t, bf);
      char name[64];
      std::snprintf(name, sizeof name, "/snapshot_%02zu_beam.csv", frame);
      write_beam_snapshot<Dim>(dir + name, c.solid());
      std::snprintf(name, sizeof name, "/snapshot_%02zu_fluid.csv", frame);
      CsvWriter fluid_csv(dir + name, with_coordinates<Dim>({}, {"p_Pa"}));
      const auto& fx = c.fluid().particles().positions();
      for (std::size_t i = 0; i < c.structure_offset(); ++i)
        fluid_csv.row(row_with<Dim>({}, fx[i], {c.fluid().pressure()[i]}));
      std::printf("%8.3f %11.4f %11.4f %9zu %9zu\n", 1e3 * t, 1e3 * d[1], 1e3 * d[0], c.solid().cut_bonds(),
                  c.solid().failure_events());
      state.frame_times.push_back(t);
      ++state.frames;
      state.next_output += every;
    }
    if (t >= o.end - 1e-9) break;
    c.step();
    progress.update(c.step_count(), c.time());
  }
  progress.finish();
  s.wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  s.max_tip = state.max_tip;
  s.fluid = c.fluid_seconds();
  s.solid = c.solid_seconds();
  s.cut = c.solid().cut_bonds();
  s.failures = c.solid().failure_events();
  s.first_failure = c.solid().first_failure_time();
  // The crack paths: every failure with the failing particle's reference position and stress.
  CsvWriter failures(dir + "/failures.csv", with_coordinates<Dim>({"t"}, {"sigma1_Pa", "sigma1_over_sigma_f"}, "0"));
  std::size_t near_clamp = 0, under_impact = 0;
  for (const auto& e : c.solid().failure_log()) {
    const Vec<Dim>& x0 = c.solid().reference_positions()[e.particle];
    failures.row(row_with<Dim>({e.time}, x0, {e.sigma1, e.sigma1 / ice.tensile_strength()}));
    near_clamp += x0[0] < 0.1;
    under_impact += x0[0] > beam_length - droplet_size;
  }
  if (fracture) {
    double min_ratio = 1e300;
    for (const auto& e : c.solid().failure_log()) min_ratio = std::min(min_ratio, e.sigma1 / ice.tensile_strength());
    char first[48] = "no failure";
    if (s.failures) std::snprintf(first, sizeof first, "first failure at t = %.3f ms", 1e3 * s.first_failure);
    std::printf("fracture: %s; %zu failures (%zu within 0.1 m of the clamp, %zu under the impact), %zu bonds cut; "
                "every failure had sigma_1 / sigma_f >= %.3f\n",
                first, s.failures, near_clamp, under_impact, s.cut, s.failures ? min_ratio : 0.0);
    std::printf("enclosed fluid (trapped among fragments, left out of the PPE with P = 0): %lld of %lld steps, "
                "%zu particles at the end\n",
                c.fluid().steps_with_enclosed_regions(), c.fluid().step_count(), c.fluid().enclosed_particles().size());
  }
  std::printf("wall time %.1f s: fluid %.1f s, structure %.1f s, rest (output) %.1f s; max |tip dy| %.2f mm\n", s.wall,
              s.fluid, s.solid, s.wall - s.fluid - s.solid, 1e3 * s.max_tip);
  return s;
}

template <int Dim, class Scheme>
int run_both(const Options& o) {
  if (o.only != "with")
    if (const auto s = run<Dim, SolidDefaults<Dim>, Scheme>(o, false, o.out + "/without_fracture"); s.stop_code)
      return s.stop_code;
  if (o.only != "without")
    if (const auto s = run<Dim, BrittleSolidPolicies<Dim>, Scheme>(o, true, o.out + "/with_fracture"); s.stop_code)
      return s.stop_code;
  std::printf("\nwrote %s/{without,with}_fracture; render with python3 examples/droplet_on_ice_beam/plot.py %s\n",
              o.out.c_str(), o.out.c_str());
  return 0;
}

}  // namespace

int main(int argc, char** argv) try {
  Options o;
  mpsfsi_examples::CaseOptions cli("droplet_on_ice_beam",
                                   "A water droplet falling on a cantilever ice beam, without and with brittle fracture "
                                   "(the paper's Figs 10-14)");
  using mpsfsi_examples::one_of;
  using mpsfsi_examples::positive;
  cli.add("--dim", o.dim, "dimension (3: the 2D case extruded along z over --width)")->check(one_of({"2", "3"}));
  cli.add("--l0", o.l0, "particle spacing; 0: 0.0025 in 2D, 0.005 in 3D", "m")->check(mpsfsi_examples::non_negative());
  cli.add("--width", o.width, "3D: width of beam and droplet along z", "m")->check(positive());
  cli.add("--dt", o.dt, "fluid (coupling) time step; 0: automatic (Courant 0.2)", "s")->check(mpsfsi_examples::non_negative());
  cli.add("--end", o.end, "end time", "s")->check(positive());
  cli.add("--gap", o.gap, "droplet bottom above the beam at t = 0", "m")->check(mpsfsi_examples::non_negative());
  cli.add("--speed", o.speed, "droplet speed, downwards", "m/s");
  cli.add("--scheme", o.scheme, "coupling scheme: explicit (the paper's) or sub-iterated")
      ->check(one_of({"explicit", "iterated"}));
  cli.add("--only", o.only, "run one of the two: with or without fracture; both if empty")
      ->check(one_of({"", "with", "without"}));
  cli.add("--plane", o.plane, "2D plane model of the beam (2D only)")->check(one_of({"stress", "strain"}));
  cli.add("--failure-stress", o.failure_stress, "where the failure criterion reads the stress")
      ->check(one_of({"centre", "surface"}));
  cli.add("--crack-side", o.crack_side,
          "how a failing particle's crack plane divides its bonds (SolidParameters::crack_side)")
      ->check(one_of({"slab", "fixed-sign", "attachment"}));
  cli.add("--solid-courant", o.solid_courant,
          "structure step dt_s = C l0 / c (c the P-wave speed); 0: the library's default (0.25)")
      ->check(mpsfsi_examples::non_negative());
  cli.add("--checkpoint-every", o.checkpoint_every,
          "simulated time between checkpoints (<run folder>/checkpoint_<step>.bin); 0: only on Ctrl-C / SIGTERM", "s")
      ->check(mpsfsi_examples::non_negative());
  cli.add("--restart", o.restart, "checkpoint to continue from, with --only naming its run (same options otherwise)");
  cli.add("--out", o.out, "output folder");
  if (const auto code = cli.parse_or_exit_code(argc, argv)) return *code;
  if (!o.restart.empty() && o.only.empty()) {
    std::fprintf(stderr, "droplet_on_ice_beam: --restart needs --only with|without (the run the checkpoint belongs to)\n");
    return 2;
  }
  if (o.dim == 3 && o.plane != "stress") {
    std::fprintf(stderr, "droplet_on_ice_beam: --plane %s: the plane model is a 2D option; a 3D beam has none\n",
                 o.plane.c_str());
    return 2;
  }
  if (o.l0 == 0) o.l0 = o.dim == 2 ? 0.0025 : 0.005;
  if (cli.print_case_if_requested()) return 0;
  mpsfsi_examples::make_output_folder(o.out);
  cli.write_case(o.out);
  std::fprintf(stderr, "%s\n", ProgressReporter::legend());
  if (o.dim == 3)
    return o.scheme == "explicit" ? run_both<3, ExplicitPartitioned>(o) : run_both<3, SubIterated>(o);
  return o.scheme == "explicit" ? run_both<2, ExplicitPartitioned>(o) : run_both<2, SubIterated>(o);
} catch (const mpsfsi::SimulationError& e) {
  std::fprintf(stderr, "droplet_on_ice_beam: %s\n(the last good snapshot is the last one in the .pvd files)\n",
               e.what());
  return 1;
} catch (const mpsfsi::Error& e) {
  std::fprintf(stderr, "droplet_on_ice_beam: %s\n", e.what());
  return 1;
}
