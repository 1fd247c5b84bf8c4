// SPDX-License-Identifier: BSD-3-Clause
#pragma once

#include <string>
#include <vector>

#include "mpsfsi/core/abi.hpp"
#include "mpsfsi/core/error.hpp"
#include "mpsfsi/core/particle_set.hpp"
#include "mpsfsi/io/pvtu_writer.hpp"
#include "mpsfsi/io/vtu_writer.hpp"
#include "mpsfsi/mpi/communicator.hpp"

namespace mpsfsi {
inline namespace MPSFSI_ABI {

// Collective: each process writes its particles as `<stem>_p<rank>.vtu` in `directory`, and
// once every piece is written, process 0 writes the index `<stem>.pvtu` that lists them
// (io/pvtu_writer.hpp). Returns the index's file name, relative to `directory` (for a PvdWriter
// there). No process holds more than its own particles. If any process cannot write, every
// process throws an Error naming it, and no index is written.
template <int Dim>
std::string write_distributed_vtu(const Communicator& comm, const std::string& directory, const std::string& stem,
                                  const ParticleSet<Dim>& particles) {
  const std::string prefix = directory.empty() || directory.back() == '/' ? directory : directory + "/";
  auto piece_name = [&stem](int rank) { return stem + "_p" + std::to_string(rank) + ".vtu"; };
  const VtuWriter<Dim, double> writer = particle_vtu_writer(particles);
  std::string error;
  try {
    writer.write(prefix + piece_name(comm.rank()));
  } catch (const Error& e) {
    error = e.what();
  }
  comm.throw_if_any_failed(error);
  const std::string index = stem + ".pvtu";
  if (comm.rank() == 0) {
    std::vector<std::string> pieces;
    for (int r = 0; r < comm.size(); ++r) pieces.push_back(piece_name(r));
    try {
      write_pvtu(prefix + index, writer, pieces);
    } catch (const Error& e) {
      error = e.what();
    }
  }
  comm.throw_if_any_failed(error);
  return index;
}

}  // namespace MPSFSI_ABI
}  // namespace mpsfsi
