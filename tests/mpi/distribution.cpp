// SPDX-License-Identifier: BSD-3-Clause
// The distribution of a particle set over MPI processes (mpi/): recursive coordinate bisection,
// migration and the halo. Run under mpirun with 1 to 4 processes; every process builds the
// same global test set (tests only: the library never holds one) and keeps a contiguous part.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>
#include <set>
#include <string>
#include <vector>

#include "mpsfsi/core/cell_list_search.hpp"
#include "mpsfsi/mpi/communicator.hpp"
#include "mpsfsi/mpi/particle_exchange.hpp"
#include "mpsfsi/mpi/rcb_decomposition.hpp"
#include "support/brute_force.hpp"

using namespace mpsfsi;

namespace {

template <int Dim>
VecArray<Dim, double> random_points(std::size_t n, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  VecArray<Dim, double> p(n);
  for (auto& x : p)
    for (int a = 0; a < Dim; ++a) x[a] = u(rng);
  return p;
}

// A lattice of spacing 0.1 (side points per axis): many particles share the coordinates of cuts.
template <int Dim>
VecArray<Dim, double> lattice_points(int side) {
  VecArray<Dim, double> p;
  const int total = Dim == 2 ? side * side : side * side * side;
  for (int k = 0; k < total; ++k) {
    Vec<Dim, double> x;
    int rest = k;
    for (int a = 0; a < Dim; ++a) {
      x[a] = 0.1 * (rest % side);
      rest /= side;
    }
    p.push_back(x);
  }
  return p;
}

// This process's contiguous part of the global points, with ids = global indices.
template <int Dim>
ParticleSet<Dim> my_part(const Communicator& comm, const VecArray<Dim, double>& global) {
  const std::size_t n = global.size();
  const std::size_t lo = n * static_cast<std::size_t>(comm.rank()) / static_cast<std::size_t>(comm.size());
  const std::size_t hi = n * static_cast<std::size_t>(comm.rank() + 1) / static_cast<std::size_t>(comm.size());
  ParticleSet<Dim> set;
  for (std::size_t i = lo; i < hi; ++i) set.add(global[i]);
  set.number_ids_from(static_cast<Index>(lo));
  return set;
}

// A displacement of each particle, the same on every process: up to `reach` per axis.
template <int Dim>
Vec<Dim, double> shift_of(Index id, double reach) {
  Vec<Dim, double> d;
  for (int a = 0; a < Dim; ++a) d[a] = reach * std::sin(1.7 * id + 2.3 * a);
  return d;
}

// Counts, over every process, the owned particles whose distributed neighbour list (owned +
// ghosts, by id) differs from the brute-force list of the global points; also checks that each
// process owns exactly the particles in its box and that no particle is lost.
template <int Dim>
long long mismatched_lists(const Communicator& comm, const RcbDecomposition<Dim>& rcb, const Halo<Dim>& halo,
                           const ParticleSet<Dim>& set, const VecArray<Dim, double>& global, double radius) {
  const auto expected = test::brute_force_neighbors<Dim, double>(global, global, radius, true);
  CellListSearch<Dim> search(radius);
  search.build(set.positions());
  NeighborList list;
  search.self_query(set.positions(), list);
  long long wrong = 0;
  for (std::size_t i = 0; i < halo.owned(); ++i) {
    if (rcb.owner(set.positions()[i]) != comm.rank()) ++wrong;
    std::vector<Index> ids;
    for (Offset b = list.begin(i); b < list.end(i); ++b) ids.push_back(set.ids()[static_cast<std::size_t>(list.indices[static_cast<std::size_t>(b)])]);
    std::sort(ids.begin(), ids.end());
    if (ids != expected[static_cast<std::size_t>(set.ids()[i])]) ++wrong;
  }
  const auto owned_total = comm.sum(static_cast<std::int64_t>(halo.owned()));
  if (owned_total != static_cast<std::int64_t>(global.size())) ++wrong;
  return comm.sum(wrong);
}

template <int Dim>
void check_neighbours(const VecArray<Dim, double>& start, double radius, const std::string& what) {
  const Communicator comm;
  VecArray<Dim, double> global = start;
  ParticleSet<Dim> set = my_part(comm, global);
  RcbDecomposition<Dim> rcb;
  rcb.build(comm, set.positions(), set.size());
  migrate(comm, rcb, set);
  Halo<Dim> halo;
  halo.build(comm, rcb, set, radius);
  INFO(what << " on " << comm.size() << " processes");
  CHECK(mismatched_lists(comm, rcb, halo, set, global, radius) == 0);
  const double imbalance = load_imbalance(comm, halo.owned());
  MESSAGE(what << ", " << comm.size() << " processes: imbalance " << imbalance << ", ghosts here " << halo.ghosts()
               << ", halo " << halo.bytes_sent(set) << " bytes in " << halo.messages_sent() << " messages");
  // The particles move (many across boxes) and migrate to the boxes of the same decomposition.
  halo.drop(set);
  for (std::size_t i = 0; i < set.size(); ++i) set.positions()[i] += shift_of<Dim>(set.ids()[i], 0.6 * radius);
  for (std::size_t i = 0; i < global.size(); ++i) global[i] += shift_of<Dim>(static_cast<Index>(i), 0.6 * radius);
  const auto moved = comm.sum(static_cast<std::int64_t>(migrate(comm, rcb, set)));
  if (comm.size() > 1) CHECK(moved > 0);
  halo.build(comm, rcb, set, radius);
  CHECK(mismatched_lists(comm, rcb, halo, set, global, radius) == 0);
}

}  // namespace

TEST_SUITE("mpi") {

TEST_CASE("mpi.rcb: equal shares of random points and shares within a row on a lattice") {
  const Communicator comm;
  {
    const auto global = random_points<3>(6000, 11);
    ParticleSet<3> set = my_part(comm, global);
    RcbDecomposition<3> rcb;
    rcb.build(comm, set.positions(), set.size());
    migrate(comm, rcb, set);
    // Distinct random coordinates: each box gets round(share), so counts differ by at most one
    // per level of the tree.
    const auto most = comm.max(static_cast<std::int64_t>(set.size()));
    const auto least = comm.min(static_cast<std::int64_t>(set.size()));
    CHECK(most - least <= 2);
  }
  {
    const auto global = lattice_points<2>(40);
    ParticleSet<2> set = my_part(comm, global);
    RcbDecomposition<2> rcb;
    rcb.build(comm, set.positions(), set.size());
    migrate(comm, rcb, set);
    // A cut cannot split a row of 40 particles sharing its coordinate.
    const auto most = comm.max(static_cast<std::int64_t>(set.size()));
    const auto least = comm.min(static_cast<std::int64_t>(set.size()));
    CHECK(most - least <= 2 * 40);
  }
}

TEST_CASE("mpi.neighbours: distributed lists equal brute force on random and lattice sets") {
  check_neighbours<2>(random_points<2>(1500, 3), 0.06, "2D random");
  check_neighbours<3>(random_points<3>(1500, 5), 0.15, "3D random");
  check_neighbours<2>(lattice_points<2>(30), 0.21, "2D lattice");
  check_neighbours<3>(lattice_points<3>(11), 0.21, "3D lattice");
}

TEST_CASE("mpi.migration: every field of every particle survives migration and the halo") {
  const Communicator comm;
  constexpr int D = 3;
  const auto global = random_points<D>(3000, 17);
  ParticleSet<D> set = my_part(comm, global);
  const auto s = set.add_field<double>("s");
  const auto v = set.add_field<Vec<D, double>>("v");
  const auto t = set.add_field<Mat<D, double>>("t");
  const auto k = set.add_field<std::int32_t>("k");
  // Each field a function of the id: a value that arrives with the wrong particle is caught.
  auto fill = [&](std::size_t i) {
    const double id = set.ids()[i];
    set.velocities()[i] = Vec<D, double>(std::cos(id), id, -id);
    set.kinds()[i] = static_cast<ParticleKind>(set.ids()[i] % 4);
    set.field(s)[i] = std::sqrt(id + 0.5);
    set.field(v)[i] = Vec<D, double>(id, 2 * id, 3 * id);
    set.field(t)[i] = Mat<D, double>::Constant(id) + Mat<D, double>::Identity();
    set.field(k)[i] = 7 * set.ids()[i] + 1;
  };
  auto intact = [&](std::size_t i) {
    const Index id = set.ids()[i];
    const double d = id;
    return set.velocities()[i] == Vec<D, double>(std::cos(d), d, -d) && set.kinds()[i] == static_cast<ParticleKind>(id % 4) &&
           set.field(s)[i] == std::sqrt(d + 0.5) && set.field(v)[i] == Vec<D, double>(d, 2 * d, 3 * d) &&
           set.field(t)[i] == Mat<D, double>::Constant(d) + Mat<D, double>::Identity() && set.field(k)[i] == 7 * id + 1;
  };
  for (std::size_t i = 0; i < set.size(); ++i) fill(i);
  RcbDecomposition<D> rcb;
  Halo<D> halo;
  for (int round = 0; round < 3; ++round) {
    rcb.build(comm, set.positions(), set.size());
    migrate(comm, rcb, set);
    halo.build(comm, rcb, set, 0.1);
    long long broken = 0;
    for (std::size_t i = 0; i < set.size(); ++i) broken += intact(i) ? 0 : 1;  // owned and ghosts
    CHECK(comm.sum(broken) == 0);
    // Every id once: the count, the sum and the sum of squares of the owned ids.
    std::int64_t count = 0, sum = 0, squares = 0;
    for (std::size_t i = 0; i < halo.owned(); ++i) {
      const std::int64_t id = set.ids()[i];
      ++count;
      sum += id;
      squares += id * id;
    }
    const std::int64_t n = static_cast<std::int64_t>(global.size());
    CHECK(comm.sum(count) == n);
    CHECK(comm.sum(sum) == n * (n - 1) / 2);
    CHECK(comm.sum(squares) == (n - 1) * n * (2 * n - 1) / 6);
    // A refresh after the owners change a field (negated, which is exact): the ghosts follow.
    for (std::size_t i = 0; i < halo.owned(); ++i) set.field(s)[i] = -set.field(s)[i];
    halo.refresh(comm, set);
    broken = 0;
    for (std::size_t i = 0; i < set.size(); ++i) broken += set.field(s)[i] == -std::sqrt(set.ids()[i] + 0.5) ? 0 : 1;
    CHECK(comm.sum(broken) == 0);
    for (std::size_t i = 0; i < halo.owned(); ++i) set.field(s)[i] = -set.field(s)[i];
    // Mirror every particle through the centre: nearly all change process.
    halo.drop(set);
    for (auto& x : set.positions()) x = Vec<D, double>::Constant(1.0) - x;
  }
}

TEST_CASE("mpi.communicator: an error on one process stops every process with its message") {
  const Communicator comm;
  const int failing = comm.size() - 1;
  std::string caught;
  try {
    comm.throw_if_any_failed(comm.rank() == failing ? "particle 42 is not finite" : "");
  } catch (const Error& e) {
    caught = e.what();
  }
  CHECK(caught == "rank " + std::to_string(failing) + ": particle 42 is not finite");
  CHECK_NOTHROW(comm.throw_if_any_failed(""));
}

}  // TEST_SUITE
