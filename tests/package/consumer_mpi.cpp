// SPDX-License-Identifier: BSD-3-Clause
// Downstream use of the optional distribution over MPI: cuts a small set over the processes and
// moves each particle to its box.
#include <cstdio>

#include <mpi.h>
#include <mpsfsi/mpsfsi.hpp>
#include <mpsfsi/mpi/particle_exchange.hpp>

int main(int argc, char** argv) {
  MPI_Init(&argc, &argv);
  const mpsfsi::Communicator comm;
  mpsfsi::ParticleSet<2> set;
  for (int k = 0; k < 100; ++k) set.add(mpsfsi::Vec<2, double>(0.01 * k, 0.5));
  set.number_ids_from(static_cast<mpsfsi::Index>(100 * comm.rank()));
  mpsfsi::RcbDecomposition<2> rcb;
  rcb.build(comm, set.positions(), set.size());
  mpsfsi::migrate(comm, rcb, set);
  const auto total = comm.sum(static_cast<long long>(set.size()));
  if (comm.rank() == 0) std::printf("%lld particles on %d processes\n", total, comm.size());
  MPI_Finalize();
  return total == 100LL * comm.size() ? 0 : 1;
}
