// SPDX-License-Identifier: BSD-3-Clause
#pragma once

#include <cstdint>
#include <cstring>
#include <limits>
#include <string>
#include <type_traits>
#include <vector>

#include "mpsfsi/core/abi.hpp"
#include "mpsfsi/core/error.hpp"
#include "mpsfsi/core/particle_set.hpp"
#include "mpsfsi/core/types.hpp"
#include "mpsfsi/mpi/communicator.hpp"
#include "mpsfsi/mpi/rcb_decomposition.hpp"

namespace mpsfsi {
inline namespace MPSFSI_ABI {

namespace detail {

// Who sends how many particles to whom, and the buffers of one exchange: particles are packed
// whole (ParticleSet::pack), so every field travels, typed extra fields included.
struct ExchangePlan {
  std::vector<int> send_ranks, recv_ranks;
  std::vector<std::size_t> send_offsets{0};  // into send_index, per entry of send_ranks
  std::vector<std::size_t> send_index;       // the particles to pack, grouped by destination
  std::vector<std::size_t> recv_counts;      // particles, per entry of recv_ranks
  std::size_t received = 0;

  // From per-destination lists (collective: every process learns who sends to it).
  void set_sends(const Communicator& comm, const std::vector<std::vector<std::size_t>>& to_rank) {
    send_ranks.clear();
    send_offsets.assign(1, 0);
    send_index.clear();
    std::vector<std::uint64_t> counts(static_cast<std::size_t>(comm.size()), 0), incoming(counts.size(), 0);
    for (std::size_t r = 0; r < to_rank.size(); ++r) {
      counts[r] = to_rank[r].size();
      if (to_rank[r].empty()) continue;
      send_ranks.push_back(static_cast<int>(r));
      send_index.insert(send_index.end(), to_rank[r].begin(), to_rank[r].end());
      send_offsets.push_back(send_index.size());
    }
    MPI_Alltoall(counts.data(), 1, MPI_UINT64_T, incoming.data(), 1, MPI_UINT64_T, comm.get());
    recv_ranks.clear();
    recv_counts.clear();
    received = 0;
    for (std::size_t r = 0; r < incoming.size(); ++r) {
      if (incoming[r] == 0) continue;
      recv_ranks.push_back(static_cast<int>(r));
      recv_counts.push_back(incoming[r]);
      received += incoming[r];
    }
  }

  // Packs the listed particles of `set`, sends them, and receives into `in`
  // (received x packed_size bytes, in the order of recv_ranks).
  template <int Dim>
  void run(const Communicator& comm, const ParticleSet<Dim>& set, std::vector<unsigned char>& out,
           std::vector<unsigned char>& in) const {
    run_bytes(comm, set.packed_size(), [&set](std::size_t i, unsigned char* to) { set.pack(i, to); }, out, in);
  }

  // The same with `bytes` per item written by pack(i, to). Point-to-point with the processes in
  // the plan only.
  template <class Pack>
  void run_bytes(const Communicator& comm, std::size_t bytes, Pack&& pack, std::vector<unsigned char>& out,
                 std::vector<unsigned char>& in) const {
    out.resize(send_index.size() * bytes);
    for (std::size_t k = 0; k < send_index.size(); ++k) pack(send_index[k], out.data() + k * bytes);
    in.resize(received * bytes);
    requests_.clear();
    requests_.reserve(send_ranks.size() + recv_ranks.size());
    std::size_t at = 0;
    for (std::size_t k = 0; k < recv_ranks.size(); ++k) {
      requests_.emplace_back();
      MPI_Irecv(in.data() + at, message_length(recv_counts[k] * bytes), MPI_BYTE, recv_ranks[k], kTag, comm.get(),
                &requests_.back());
      at += recv_counts[k] * bytes;
    }
    for (std::size_t k = 0; k < send_ranks.size(); ++k) {
      requests_.emplace_back();
      MPI_Isend(out.data() + send_offsets[k] * bytes, message_length((send_offsets[k + 1] - send_offsets[k]) * bytes),
                MPI_BYTE, send_ranks[k], kTag, comm.get(), &requests_.back());
    }
    MPI_Waitall(static_cast<int>(requests_.size()), requests_.data(), MPI_STATUSES_IGNORE);
    bytes_sent_total += out.size();
    messages_sent_total += send_ranks.size();
  }

  static int message_length(std::size_t bytes) {
    if (bytes > static_cast<std::size_t>(std::numeric_limits<int>::max()))
      throw_invalid("particle exchange", "a message of " + std::to_string(bytes) +
                                             " bytes exceeds MPI's int count: use more processes");
    return static_cast<int>(bytes);
  }
  static constexpr int kTag = 7301;
  mutable std::vector<MPI_Request> requests_;  // kept: a refresh allocates nothing once sized
  // Sent by every run() since the plan was made, over all the plans it held (set_sends keeps them).
  mutable std::size_t bytes_sent_total = 0, messages_sent_total = 0;
};

}  // namespace detail

// Moves every particle of `set` to the process whose box holds it (collective), with all its
// fields and its id. The particles that stay keep their order; the arrivals follow them, by
// source rank. `set` must hold no ghosts (Halo::drop). Returns the number of particles sent.
template <int Dim>
std::size_t migrate(const Communicator& comm, const RcbDecomposition<Dim>& decomposition, ParticleSet<Dim>& set) {
  const auto& x = set.positions();
  std::vector<std::vector<std::size_t>> to_rank(static_cast<std::size_t>(comm.size()));
  std::vector<Index> order;
  order.reserve(set.size());
  for (std::size_t i = 0; i < set.size(); ++i) {
    const int owner = decomposition.owner(x[i]);
    if (owner == comm.rank())
      order.push_back(static_cast<Index>(i));
    else
      to_rank[static_cast<std::size_t>(owner)].push_back(i);
  }
  detail::ExchangePlan plan;
  plan.set_sends(comm, to_rank);
  std::vector<unsigned char> out, in;
  plan.run(comm, set, out, in);
  const std::size_t kept = order.size();
  for (const std::size_t i : plan.send_index) order.push_back(static_cast<Index>(i));
  set.permute(order);
  set.resize(kept);
  const std::size_t bytes = set.packed_size();
  set.reserve(kept + plan.received);
  for (std::size_t k = 0; k < plan.received; ++k) set.unpack(in.data() + k * bytes);
  return plan.send_index.size();
}

// Ghost copies of the particles of other processes within a radius of this process's box, so
// that a neighbour search over owned + ghost particles finds, for every owned particle, all its
// neighbours within that radius, and every operator runs unchanged on one process. build()
// appends the ghosts after the owned particles; refresh() gives them their owners' current
// values (before each pass that reads neighbour values); drop() removes them before particles
// migrate. A particle is sent to each process whose box lies within the radius of it.
template <int Dim>
class Halo {
 public:
  // Collective. `set` holds this process's own particles only.
  void build(const Communicator& comm, const RcbDecomposition<Dim>& decomposition, ParticleSet<Dim>& set, double radius) {
    if (!(radius > 0)) detail::throw_invalid("Halo::build", "the halo radius must be positive");
    owned_ = set.size();
    std::vector<std::vector<std::size_t>> to_rank(static_cast<std::size_t>(comm.size()));
    const auto& x = set.positions();
    // Widened by the round-off of the distance to a box, so that a pair at exactly the radius
    // (which CellListSearch includes) is never missed.
    const double reach = radius * (1 + 1e-12);
    for (std::size_t i = 0; i < owned_; ++i)
      decomposition.for_each_rank_within(x[i], reach, [&](int r) {
        if (r != comm.rank()) to_rank[static_cast<std::size_t>(r)].push_back(i);
      });
    plan_.set_sends(comm, to_rank);
    plan_.run(comm, set, send_buffer_, recv_buffer_);
    const std::size_t bytes = set.packed_size();
    set.reserve(owned_ + plan_.received);
    for (std::size_t k = 0; k < plan_.received; ++k) set.unpack(recv_buffer_.data() + k * bytes);
  }

  // Collective: every ghost takes its owner's current fields (positions, velocities, extra fields).
  void refresh(const Communicator& comm, ParticleSet<Dim>& set) {
    if (set.size() != owned_ + plan_.received)
      detail::throw_invalid("Halo::refresh", "the set has " + std::to_string(set.size()) + " particles, the halo was built for " +
                                                 std::to_string(owned_) + " owned and " + std::to_string(plan_.received) +
                                                 " ghosts");
    plan_.run(comm, set, send_buffer_, recv_buffer_);
    const std::size_t bytes = set.packed_size();
    for (std::size_t k = 0; k < plan_.received; ++k) set.unpack_into(owned_ + k, recv_buffer_.data() + k * bytes);
  }

  // Collective: the ghosts' entries of a solver's own per-particle array (indexed like the set,
  // at least owned() + ghosts() long) take their owners' values.
  template <class T, class Alloc>
  void refresh_array(const Communicator& comm, std::vector<T, Alloc>& values) {
    static_assert(std::is_trivially_copyable_v<T> || std::is_same_v<T, Vec<Dim, double>> ||
                      std::is_same_v<T, Mat<Dim, double>>,
                  "Halo::refresh_array copies values byte-wise");
    if (values.size() < owned_ + plan_.received)
      detail::throw_invalid("Halo::refresh_array", "the array has " + std::to_string(values.size()) + " entries for " +
                                                       std::to_string(owned_) + " owned particles and " +
                                                       std::to_string(plan_.received) + " ghosts");
    plan_.run_bytes(
        comm, sizeof(T), [&values](std::size_t i, unsigned char* to) { std::memcpy(to, static_cast<const void*>(&values[i]), sizeof(T)); },
        send_buffer_, recv_buffer_);
    for (std::size_t k = 0; k < plan_.received; ++k)
      std::memcpy(static_cast<void*>(&values[owned_ + k]), recv_buffer_.data() + k * sizeof(T), sizeof(T));
  }

  void drop(ParticleSet<Dim>& set) const { set.resize(owned_); }

  std::size_t owned() const { return owned_; }
  std::size_t ghosts() const { return plan_.received; }
  // What one refresh sends from this process: bytes, and messages (one per neighbouring process).
  std::size_t bytes_sent(const ParticleSet<Dim>& set) const { return plan_.send_index.size() * set.packed_size(); }
  std::size_t messages_sent() const { return plan_.send_ranks.size(); }
  // Everything this process has sent through the halo so far (builds and refreshes of any kind).
  std::size_t total_bytes_sent() const { return plan_.bytes_sent_total; }
  std::size_t total_messages_sent() const { return plan_.messages_sent_total; }

 private:
  std::size_t owned_ = 0;
  detail::ExchangePlan plan_;
  std::vector<unsigned char> send_buffer_, recv_buffer_;
};

}  // namespace MPSFSI_ABI
}  // namespace mpsfsi
