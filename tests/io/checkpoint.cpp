// SPDX-License-Identifier: BSD-3-Clause
#include "mpsfsi/io/checkpoint.hpp"

#include <doctest/doctest.h>

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "mpsfsi/fluid/fluid_solver.hpp"
#include "mpsfsi/fracture/fracture_process.hpp"
#include "mpsfsi/fsi/fsi_coupler.hpp"
#include "mpsfsi/io/vtu_writer.hpp"
#include "mpsfsi/scenes/dam_break.hpp"
#include "mpsfsi/scenes/hydrostatic_plate.hpp"
#include "mpsfsi/scenes/solid_block.hpp"
#include "mpsfsi/solid/elastic_solver.hpp"

using namespace mpsfsi;

namespace {

// A small dam break: 0.1 m x 0.2 m of water in a tank 0.4 m x 0.3 m (3D: 0.05 m deep), l0 = 1 cm.
template <int Dim, class Policies = FluidDefaults<Dim>>
FluidSolver<Dim, Policies> small_dam_break() {
  FluidParameters<Dim> p;
  p.l0 = 0.01;
  return FluidSolver<Dim, Policies>(scenes::dam_break<Dim>(0.1, 0.2, 0.4, 0.3, 0.01, 0.05), p);
}

std::vector<char> file_bytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  REQUIRE(in);
  return std::vector<char>(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

void write_bytes(const std::string& path, const std::vector<char>& bytes) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
}

struct JacobiPolicies : FluidDefaults<2> {
  using linear_solver = JacobiCg;
};

// The quick start's notched ice bar (0.1 m x 0.02 m, Table 1 case 02 ice, l0 = 2 mm), clamped at
// the left end and pulled at the right at 0.05 m/s until it breaks.
ElasticSolver<2, BrittleSolidPolicies<2>> notched_bar() {
  const double l0 = 0.002;
  const auto ice = scenes::material_block<2>(Vec<2>(-0.05, 0), Vec<2>(0.05, 0.02), l0);
  SolidParameters<2> p;
  p.l0 = l0;
  p.density = 917;
  p.youngs_modulus = 270e6;
  p.poisson_ratio = 0.3;
  p.tensile_strength = 1.14e6;
  p.plane_model = PlaneModel::plane_stress;
  ElasticSolver<2, BrittleSolidPolicies<2>> bar(ice, p);
  for (auto i : scenes::select(ice, [](const Vec<2>& x) { return x[0] < -0.044; })) bar.clamp(i);
  for (auto i : scenes::select(ice, [](const Vec<2>& x) { return x[0] > 0.044; }))
    bar.prescribe_velocity(i, Vec<2>(0.05, 0));
  bar.impose_crack(scenes::select(ice, [](const Vec<2>& x) { return x.norm() < 0.002; })[0], Vec<2>(1, 0));
  return bar;
}

}  // namespace

TEST_SUITE("io") {

TEST_CASE("io.checkpoint: a dam break continued from a checkpoint gives the same bits as one run straight through") {
  constexpr int steps = 40;
  auto straight = small_dam_break<2>();
  for (int k = 0; k < steps; ++k) straight.step();

  const std::string path = "io_checkpoint_dam_break.bin";
  {
    auto first_half = small_dam_break<2>();
    for (int k = 0; k < steps / 2; ++k) first_half.step();
    write_checkpoint(path, first_half);
  }
  auto resumed = small_dam_break<2>();  // built as the run that wrote the checkpoint, then restored
  read_checkpoint(path, resumed);
  CHECK(resumed.step_count() == steps / 2);
  for (int k = 0; k < steps / 2; ++k) resumed.step();

  CHECK(resumed.time() == straight.time());
  CHECK(resumed.step_count() == straight.step_count());
  CHECK(resumed.particles().positions() == straight.particles().positions());
  CHECK(resumed.particles().velocities() == straight.particles().velocities());
  CHECK(resumed.pressure() == straight.pressure());
  write_vtu("io_checkpoint_straight.vtu", straight.particles());
  write_vtu("io_checkpoint_resumed.vtu", resumed.particles());
  CHECK(file_bytes("io_checkpoint_straight.vtu") == file_bytes("io_checkpoint_resumed.vtu"));
}

TEST_CASE("io.checkpoint: a breaking ice bar continued from a checkpoint past its first crack gives the same bits") {
  auto straight = notched_bar();
  while (straight.first_failure_time() < 0) straight.step();
  const long long first_failure_step = straight.step_count();
  const long long checkpoint_step = first_failure_step + 100, end_step = first_failure_step + 600;
  while (straight.step_count() < end_step) straight.step();
  REQUIRE(straight.failure_events() > 1);

  const std::string path = "io_checkpoint_bar.bin";
  {
    auto first_part = notched_bar();
    while (first_part.step_count() < checkpoint_step) first_part.step();
    REQUIRE(first_part.cut_bonds() > 0);
    write_checkpoint(path, first_part);
  }
  auto resumed = notched_bar();
  read_checkpoint(path, resumed);
  CHECK(resumed.step_count() == checkpoint_step);
  while (resumed.step_count() < end_step) resumed.step();

  CHECK(resumed.time() == straight.time());
  CHECK(resumed.cut_bonds() == straight.cut_bonds());
  CHECK(resumed.failure_events() == straight.failure_events());
  CHECK(resumed.first_failure_time() == straight.first_failure_time());
  CHECK(resumed.particles().positions() == straight.particles().positions());
  CHECK(resumed.particles().velocities() == straight.particles().velocities());
  write_vtu("io_checkpoint_bar_straight.vtu", straight.output());
  write_vtu("io_checkpoint_bar_resumed.vtu", resumed.output());
  CHECK(file_bytes("io_checkpoint_bar_straight.vtu") == file_bytes("io_checkpoint_bar_resumed.vtu"));
  MESSAGE("notched bar: first failure at step " << first_failure_step << ", checkpoint at " << checkpoint_step << ", "
                                                << straight.failure_events() << " failures and " << straight.cut_bonds()
                                                << " cut bonds by step " << end_step);
}

// A water column 0.05 m high on a clamped plate 0.1 m x 0.02 m (the hydrostatic-plate scene scaled
// down, l0 = 1 cm, fluid step 1 ms), coupled by `Scheme`.
template <class Scheme>
FsiCoupler<FluidSolver<2>, ElasticSolver<2>, Scheme> small_plate() {
  scenes::HydrostaticPlate scene;
  scene.span = 0.1;
  scene.water_height = 0.05;
  scene.thickness = 0.02;
  scene.youngs_modulus = 1e8;
  const double l0 = 0.01;
  SolidParameters<2> sp;
  sp.l0 = l0;
  scene.set_material(sp);
  std::vector<std::size_t> clamped;
  std::size_t middle = 0;
  ElasticSolver<2> plate(scene.plate_particles(l0, clamped, middle), sp);
  for (auto i : clamped) plate.clamp(i);
  FluidParameters<2> fp;
  fp.l0 = l0;
  fp.dt = 1e-3;
  return FsiCoupler<FluidSolver<2>, ElasticSolver<2>, Scheme>(scene.fluid_particles(l0), fp, std::move(plate));
}

TEST_CASE_TEMPLATE("io.checkpoint: a coupled plate continued from a checkpoint gives the same bits", Scheme,
                   ExplicitPartitioned, SubIterated, InterfaceQuasiNewton) {
  constexpr int steps = 12;
  auto straight = small_plate<Scheme>();
  for (int k = 0; k < steps; ++k) straight.step();
  const std::string path = "io_checkpoint_plate.bin";
  {
    auto first_half = small_plate<Scheme>();
    for (int k = 0; k < steps / 2; ++k) first_half.step();
    write_checkpoint(path, first_half);
  }
  auto resumed = small_plate<Scheme>();
  read_checkpoint(path, resumed);
  for (int k = 0; k < steps / 2; ++k) resumed.step();
  CHECK(resumed.step_count() == straight.step_count());
  CHECK(resumed.time() == straight.time());
  CHECK(resumed.last_iterations() == straight.last_iterations());
  CHECK(resumed.fluid().particles().positions() == straight.fluid().particles().positions());
  CHECK(resumed.fluid().pressure() == straight.fluid().pressure());
  CHECK(resumed.solid().particles().positions() == straight.solid().particles().positions());
  CHECK(resumed.solid().particles().velocities() == straight.solid().particles().velocities());
}

TEST_CASE("io.checkpoint: a file that does not match the solver, or is damaged, is a clear error") {
  auto solver = small_dam_break<2>();
  solver.step();
  const std::string path = "io_checkpoint_errors.bin";
  write_checkpoint(path, solver);
  const std::vector<char> good = file_bytes(path);
  const auto fails_with = [&](const std::vector<char>& bytes, const char* what) {
    const std::string damaged = "io_checkpoint_damaged.bin";
    write_bytes(damaged, bytes);
    auto target = small_dam_break<2>();
    const auto before = target.particles().positions();
    CHECK_THROWS_WITH_AS(read_checkpoint(damaged, target), doctest::Contains(what), InvalidInput);
    CHECK(target.particles().positions() == before);  // untouched
    CHECK(target.step_count() == 0);
  };
  SUBCASE("truncated") {
    fails_with(std::vector<char>(good.begin(), good.end() - 100), "truncated");
    fails_with(std::vector<char>(good.begin(), good.begin() + 20), "ends");
  }
  SUBCASE("one byte changed") {
    auto bytes = good;
    bytes[bytes.size() / 2] ^= 0x10;
    fails_with(bytes, "checksum");
  }
  SUBCASE("not a checkpoint") { fails_with(std::vector<char>{'h', 'e', 'l', 'l', 'o'}, "not an mpsfsi checkpoint"); }
  SUBCASE("a newer format version") {
    auto bytes = good;
    bytes[8] = static_cast<char>(checkpoint_format_version + 1);
    const std::string newer = std::to_string(checkpoint_format_version + 1);
    const std::string current = std::to_string(checkpoint_format_version);
    fails_with(bytes, ("format version " + newer + "; this build reads versions up to " + current).c_str());
  }
  SUBCASE("an older format version than this build reads") {
    auto bytes = good;
    bytes[8] = static_cast<char>(oldest_readable_checkpoint_format - 1);
    fails_with(bytes, ("format version " + std::to_string(oldest_readable_checkpoint_format - 1) + ", older").c_str());
  }
  SUBCASE("another dimension, policy bundle or particle count") {
    auto three_d = small_dam_break<3>();
    write_checkpoint("io_checkpoint_3d.bin", three_d);
    fails_with(file_bytes("io_checkpoint_3d.bin"), "holds a 3D state, this solver is 2D");
    auto jacobi = small_dam_break<2, JacobiPolicies>();
    write_checkpoint("io_checkpoint_jacobi.bin", jacobi);
    fails_with(file_bytes("io_checkpoint_jacobi.bin"), "(another policy bundle)");
    FluidParameters<2> p;
    p.l0 = 0.01;
    FluidSolver<2> other(scenes::dam_break<2>(0.1, 0.1, 0.4, 0.3, 0.01), p);
    write_checkpoint("io_checkpoint_other.bin", other);
    fails_with(file_bytes("io_checkpoint_other.bin"), "particles, this solver has");
    auto bar = notched_bar();
    write_checkpoint("io_checkpoint_solid.bin", bar);
    fails_with(file_bytes("io_checkpoint_solid.bin"), "holds ElasticSolver state, this solver is a FluidSolver");
  }
  SUBCASE("a missing file is an IoError") {
    CHECK_THROWS_AS(read_checkpoint("io_checkpoint_missing.bin", solver), IoError);
  }
}

// A program's own state rides along in the same file.
struct Counters {
  long long frames = 0;
  std::vector<double> times;
  template <class Archive>
  void checkpoint_state(Archive& a) {
    a.value(frames);
    a.array(times);
  }
};

TEST_CASE("io.checkpoint: further objects are written after the solver and read back in order") {
  auto solver = small_dam_break<2>();
  solver.step();
  Counters written{3, {0.0, 0.5, 1.0}};
  write_checkpoint("io_checkpoint_extra.bin", solver, written);
  auto target = small_dam_break<2>();
  Counters read;
  read_checkpoint("io_checkpoint_extra.bin", target, read);
  CHECK(read.frames == 3);
  CHECK(read.times == written.times);
  CHECK(target.step_count() == 1);
  auto other = small_dam_break<2>();
  CHECK_THROWS_WITH_AS(read_checkpoint("io_checkpoint_extra.bin", other), doctest::Contains("data left over"),
                       InvalidInput);
  CHECK(other.step_count() == 0);
}

TEST_CASE("io.checkpoint: a write that fails leaves the previous checkpoint in place") {
  auto solver = small_dam_break<2>();
  const std::string path = "io_checkpoint_previous.bin";
  write_checkpoint(path, solver);
  const auto previous = file_bytes(path);
  // The temporary file cannot be created: a directory of its name is in the way.
  std::remove((path + ".tmp").c_str());
  REQUIRE(std::system(("mkdir -p " + path + ".tmp").c_str()) == 0);
  solver.step();
  CHECK_THROWS_AS(write_checkpoint(path, solver), IoError);
  CHECK(file_bytes(path) == previous);
  REQUIRE(std::system(("rmdir " + path + ".tmp").c_str()) == 0);
  auto restored = small_dam_break<2>();
  solver.step();
  read_checkpoint(path, restored);
  CHECK(restored.step_count() == 0);
}

}  // TEST_SUITE
