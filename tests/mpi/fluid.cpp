// SPDX-License-Identifier: BSD-3-Clause
// DistributedFluidSolver under mpirun: the hydrostatic tank (2D and 3D) against rho g (H - y) with
// the serial tolerances, and the dam break on all processes against the same run on one process.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "mpsfsi/io/checkpoint.hpp"
#include "mpsfsi/mpi/distributed_fluid_solver.hpp"
#include "mpsfsi/scenes/dam_break.hpp"
#include "mpsfsi/scenes/tank.hpp"

using namespace mpsfsi;

namespace {

// Process `rank` of `size` keeps every size-th particle of a set every process builds alike
// (tests only), with ids numbered over all processes.
template <int Dim>
ParticleSet<Dim> share_of(const ParticleSet<Dim>& all, const Communicator& comm) {
  ParticleSet<Dim> mine;
  for (std::size_t i = static_cast<std::size_t>(comm.rank()); i < all.size(); i += static_cast<std::size_t>(comm.size()))
    mine.add(all.positions()[i], all.kinds()[i], all.velocities()[i]);
  mine.number_ids_from(static_cast<Index>(comm.exclusive_prefix_sum(static_cast<std::int64_t>(mine.size()))));
  return mine;
}

// The hydrostatic tank of verification.fluid (a `width` wide column `depth` deep in a tank 1.5
// depth high, 3D: `width` square) settled for `settle` s, then the layer pressures averaged over
// `average` s: the worst layer against rho g (H - y) over the lower 80 %, relative to rho g H,
// and the column height from the top particle of each lateral column, relative to H.
struct HydrostaticFigures {
  double worst_layer = 0, height_ratio = 0;
  std::int64_t escaped = 0;
};

template <int Dim>
HydrostaticFigures hydrostatic_tank(const Communicator& comm, double width, double depth, double l0, double settle,
                                    double average, double dt) {
  ParticleSet<Dim> all;
  Vec<Dim> water = Vec<Dim>::Constant(width), tank = Vec<Dim>::Constant(width);
  water[Dim - 1] = depth;
  tank[Dim - 1] = 1.5 * depth;
  scenes::add_block<Dim, double>(all, Vec<Dim>::Zero(), water, l0, ParticleKind::fluid);
  scenes::add_tank<Dim, double>(all, tank, l0);
  FluidParameters<Dim> p;
  p.l0 = l0;
  p.dt = dt;
  DistributedFluidSolver<Dim> solver(comm, share_of(all, comm), p);
  solver.advance_to(settle);
  // Layer averages of the pressure over the averaging window (particles move between processes,
  // so the time average is taken per layer, not per particle).
  const auto layers = static_cast<std::size_t>(std::llround(depth / l0));
  std::vector<double> layer_p(layers, 0.0), layer_y(layers, 0.0), layer_n(layers, 0.0);
  while (solver.time() < settle + average - 1e-9) {
    solver.step();
    const auto& s = solver.particles();
    for (std::size_t i = 0; i < solver.owned(); ++i) {
      const double y = s.positions()[i][Dim - 1];
      if (s.kinds()[i] != ParticleKind::fluid || y > 0.8 * depth || y < 0) continue;
      const auto layer = std::min(layers - 1, static_cast<std::size_t>(y / l0));
      layer_p[layer] += solver.pressure()[i];
      layer_y[layer] += y;
      layer_n[layer] += 1;
    }
  }
  comm.sum_in_place(layer_p);
  comm.sum_in_place(layer_y);
  comm.sum_in_place(layer_n);
  HydrostaticFigures f;
  const double rho_g = p.density * p.gravity.norm();
  for (std::size_t l = 0; l < layers; ++l) {
    if (layer_n[l] == 0) continue;
    const double y = layer_y[l] / layer_n[l];
    f.worst_layer = std::max(f.worst_layer, std::abs(layer_p[l] / layer_n[l] - rho_g * (depth - y)) / (rho_g * depth));
  }
  // The top of each lateral column of the lattice (in 3D, columns over the square floor).
  const auto across = static_cast<std::size_t>(std::llround(width / l0));
  const std::size_t columns = Dim == 2 ? across : across * across;
  std::vector<double> top(columns, -1.0);
  const auto& s = solver.particles();
  for (std::size_t i = 0; i < solver.owned(); ++i) {
    if (s.kinds()[i] != ParticleKind::fluid) continue;
    const Vec<Dim>& x = s.positions()[i];
    bool inside = x[Dim - 1] > 0 && x[Dim - 1] < 1.5 * depth;
    std::size_t column = 0;
    for (int k = Dim - 2; k >= 0; --k) {
      inside = inside && x[k] > 0 && x[k] < width;
      column = column * across + std::min(across - 1, static_cast<std::size_t>(std::max(0.0, x[k] / l0)));
    }
    f.escaped += inside ? 0 : 1;
    top[column] = std::max(top[column], x[Dim - 1]);
  }
  comm.max_in_place(top);
  double top_sum = 0;
  for (const double t : top) top_sum += t;
  f.height_ratio = (top_sum / static_cast<double>(columns) + 0.5 * l0) / depth;
  f.escaped = comm.sum(f.escaped);
  MESSAGE(comm.size() << " processes: hydrostatic tank " << Dim << "D, " << solver.step_count() << " steps, worst layer "
                      << f.worst_layer << ", surface height / H " << f.height_ratio << ", rebalances "
                      << solver.rebalances() << ", last PPE " << solver.last_solve().iterations << " iterations");
  return f;
}

struct DamBreakFigures {
  double front = 0, height = 0;
  long long steps = 0;
};

DamBreakFigures dam_break_at(const Communicator& comm, double end_time) {
  const double a = 0.1, l0 = a / 25;
  const auto all = scenes::dam_break<2>(a, 2 * a, 4 * a, 3 * a, l0);
  FluidParameters<2> p;
  p.l0 = l0;
  p.dt = 4e-4;
  DistributedFluidSolver<2> solver(comm, share_of(all, comm), p);
  solver.advance_to(end_time);
  ParticleSet<2> owned;
  const auto& s = solver.particles();
  for (std::size_t i = 0; i < solver.owned(); ++i) owned.add(s.positions()[i], s.kinds()[i]);
  return {comm.max(scenes::surge_front(owned, l0)), comm.max(scenes::column_height(owned, l0)), solver.step_count()};
}

}  // namespace

TEST_SUITE("mpi") {

TEST_CASE("mpi.fluid: hydrostatic tank 2D on every process") {
  // The serial case and tolerances (verification.fluid: hydrostatic tank 2D): 3 % of rho g H
  // for the layer pressures over the lower 80 %, 1 % for the column height.
  const Communicator comm;
  const HydrostaticFigures f = hydrostatic_tank<2>(comm, 0.2, 0.2, 0.005, 1.0, 0.5, 5e-4);
  CHECK(f.escaped == 0);
  CHECK(f.worst_layer < 0.03);
  CHECK(std::abs(f.height_ratio - 1) < 0.01);
}

TEST_CASE("mpi.hydrostatic3d: hydrostatic tank 3D on every process") {
  // The serial 3D case and tolerances (verification.fluid: hydrostatic tank 3D): 30 layers deep,
  // 3 % of rho g H for the layers, 1 % for the column height.
  const Communicator comm;
  const HydrostaticFigures f = hydrostatic_tank<3>(comm, 0.08, 0.24, 0.008, 1.0, 0.5, 1e-3);
  CHECK(f.escaped == 0);
  CHECK(f.worst_layer < 0.03);
  CHECK(std::abs(f.height_ratio - 1) < 0.01);
}

TEST_CASE("mpi.fluid: dam break on every process against one process") {
  // The same case on one process (each process runs it alone on MPI_COMM_SELF) and on all of
  // them: the surge front and the column height at t = 0.1 s within 1 % of the one-process run.
  // Not bit-identical: BoomerAMG's coarsening and smoothing depend on the partition.
  const Communicator all(MPI_COMM_WORLD), self(MPI_COMM_SELF);
  const DamBreakFigures one = dam_break_at(self, 0.1);
  const DamBreakFigures many = dam_break_at(all, 0.1);
  MESSAGE(all.size() << " processes against 1 at t = 0.1 s: front " << many.front << " m against " << one.front
                     << " m, column height " << many.height << " m against " << one.height << " m");
  CHECK(many.steps == one.steps);
  CHECK(std::abs(many.front / one.front - 1) <= 0.01);
  CHECK(std::abs(many.height / one.height - 1) <= 0.01);
}

TEST_CASE("mpi.fluid: a time step above the stability limit stops every process and leaves no ghost behind") {
  const Communicator comm;
  const double l0 = 0.01;
  ParticleSet<2> all;
  scenes::add_block<2, double>(all, Vec<2>::Zero(), Vec<2>(0.1, 0.1), l0, ParticleKind::fluid);
  scenes::add_tank<2, double>(all, Vec<2>(0.1, 0.15), l0);
  FluidParameters<2> p;
  p.l0 = l0;
  p.dt = 0.1;  // the Courant limit is 0.2 l0 / sqrt(g l0) = 6.4e-3 s
  DistributedFluidSolver<2> solver(comm, share_of(all, comm), p);
  bool stopped = false;
  try {
    solver.step();
  } catch (const InvalidInput& e) {
    stopped = std::string(e.what()).find("exceeds the stability limit") != std::string::npos;
  }
  CHECK(comm.min(stopped ? 1 : 0) == 1);
  CHECK(comm.sum(static_cast<std::int64_t>(solver.particles().size())) == static_cast<std::int64_t>(all.size()));
  CHECK(solver.particles().size() == solver.owned());
}

TEST_CASE("mpi.fluid: bad input stops every process with one message") {
  const Communicator comm;
  ParticleSet<2> mine;
  FluidParameters<2> p;
  p.l0 = 0.01;
  if (comm.rank() == comm.size() - 1) {
    mine.add(Vec<2>(0, 0));
    mine.add(Vec<2>(std::nan(""), 0));
  }
  mine.number_ids_from(static_cast<Index>(comm.exclusive_prefix_sum(static_cast<std::int64_t>(mine.size()))));
  std::string caught;
  try {
    DistributedFluidSolver<2> solver(comm, mine, p);
  } catch (const InvalidInput& e) {
    caught = e.what();
  }
  CHECK(caught.find("rank " + std::to_string(comm.size() - 1) + ": ") == 0);
  CHECK(caught.find("not finite") != std::string::npos);
}

TEST_CASE("mpi.fluid: a run continued from its checkpoint gives the same bits") {
  // The dam break of the test above for 40 steps, a checkpoint per process, 40 more steps (the
  // column collapsing, particles crossing between boxes); a new solver built from the
  // initial particles reads the checkpoint and takes the same 40 steps: every owned particle's
  // id, position, velocity and pressure equal to the bit.
  const Communicator comm;
  const double a = 0.1, l0 = a / 25;
  const auto all = scenes::dam_break<2>(a, 2 * a, 4 * a, 3 * a, l0);
  FluidParameters<2> p;
  p.l0 = l0;
  p.dt = 4e-4;
  const std::string dir = "mpi_checkpoint_test";
  if (comm.rank() == 0) std::filesystem::create_directories(dir);
  MPI_Barrier(comm.get());
  const std::string path = dir + "/state_p" + std::to_string(comm.rank()) + ".bin";
  const std::string next = dir + "/next_p" + std::to_string(comm.rank()) + ".bin";
  DistributedFluidSolver<2> straight(comm, share_of(all, comm), p);
  // Boxes recut at every step until the checkpoint, so that the decomposition it holds is not
  // the one a new solver builds from the initial particles: the continued run must restore it.
  straight.rebalance_threshold = -1;
  for (int k = 0; k < 40; ++k) straight.step();
  straight.rebalance_threshold = 0.1;
  std::string error;
  try {
    write_checkpoint(path, straight);
  } catch (const Error& e) {
    error = e.what();
  }
  comm.throw_if_any_failed(error);
  straight.step();
  write_checkpoint(next, straight);  // step 41, for the mixed pieces below
  for (int k = 1; k < 40; ++k) straight.step();

  DistributedFluidSolver<2> continued(comm, share_of(all, comm), p);
  try {
    read_checkpoint(path, continued);
  } catch (const Error& e) {
    error = e.what();
  }
  comm.throw_if_any_failed(error);
  CHECK_NOTHROW(continued.check_checkpoint_pieces());
  CHECK(continued.step_count() == 40);
  for (int k = 0; k < 40; ++k) continued.step();
  const auto& s = straight.particles();
  const auto& c = continued.particles();
  std::int64_t differ = s.size() == c.size() ? 0 : 1;
  for (std::size_t i = 0; i < std::min(s.size(), c.size()); ++i)
    differ += s.ids()[i] != c.ids()[i] || s.positions()[i] != c.positions()[i] || s.velocities()[i] != c.velocities()[i] ||
              straight.pressure()[i] != continued.pressure()[i];
  CHECK(comm.sum(differ) == 0);
  CHECK(straight.rebalances() >= 40);
  CHECK(continued.time() == straight.time());
  CHECK(continued.rebalances() == straight.rebalances());

  // Pieces of two checkpoints (step 40 on process 0, step 41 on the others): every process
  // throws InvalidInput.
  if (comm.size() > 1) {
    DistributedFluidSolver<2> mixed(comm, share_of(all, comm), p);
    read_checkpoint(comm.rank() == 0 ? path : next, mixed);
    CHECK_THROWS_WITH_AS(mixed.check_checkpoint_pieces(), doctest::Contains("not pieces of one checkpoint"), InvalidInput);
  }

  // A checkpoint read by a run on another number of processes: InvalidInput, the solver unchanged.
  if (comm.size() > 1) {
    const Communicator self(MPI_COMM_SELF);
    DistributedFluidSolver<2> alone(self, share_of(all, self), p);
    CHECK_THROWS_WITH_AS(read_checkpoint(path, alone), doctest::Contains("processes"), InvalidInput);
    CHECK(alone.step_count() == 0);
  }
}

}  // TEST_SUITE
