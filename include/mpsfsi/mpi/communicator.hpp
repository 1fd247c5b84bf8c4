// SPDX-License-Identifier: BSD-3-Clause
#pragma once

#include <mpi.h>

#include <cstdint>
#include <string>
#include <type_traits>
#include <vector>

#include "mpsfsi/core/abi.hpp"
#include "mpsfsi/core/error.hpp"

namespace mpsfsi {
inline namespace MPSFSI_ABI {

namespace detail {

// The MPI datatype of double and of 32- and 64-bit integers.
template <class T>
MPI_Datatype mpi_type() {
  if constexpr (std::is_same_v<T, double>) {
    return MPI_DOUBLE;
  } else {
    static_assert(std::is_integral_v<T> && (sizeof(T) == 4 || sizeof(T) == 8),
                  "mpsfsi::Communicator reduces doubles and 32- or 64-bit integers");
    if constexpr (sizeof(T) == 4) {
      return std::is_signed_v<T> ? MPI_INT32_T : MPI_UINT32_T;
    } else {
      return std::is_signed_v<T> ? MPI_INT64_T : MPI_UINT64_T;
    }
  }
}

}  // namespace detail

// The processes a distributed particle set is spread over (an MPI communicator, not owned: the
// caller initialises and finalises MPI), with the collective reductions the distribution needs.
// Every member function is collective unless it says otherwise.
class Communicator {
 public:
  explicit Communicator(MPI_Comm comm = MPI_COMM_WORLD) : comm_(comm) {
    MPI_Comm_rank(comm_, &rank_);
    MPI_Comm_size(comm_, &size_);
  }

  MPI_Comm get() const { return comm_; }  // not collective
  int rank() const { return rank_; }      // not collective
  int size() const { return size_; }      // not collective

  template <class T>
  T sum(T local) const { return reduce(local, MPI_SUM); }
  template <class T>
  T max(T local) const { return reduce(local, MPI_MAX); }
  template <class T>
  T min(T local) const { return reduce(local, MPI_MIN); }

  // Element-wise sum, min or max of a vector of the same length on every process, in place.
  template <class T>
  void sum_in_place(std::vector<T>& values) const { reduce_in_place(values, MPI_SUM); }
  template <class T>
  void min_in_place(std::vector<T>& values) const { reduce_in_place(values, MPI_MIN); }
  template <class T>
  void max_in_place(std::vector<T>& values) const { reduce_in_place(values, MPI_MAX); }

  // The sum of `local` over the processes of lower rank.
  template <class T>
  T exclusive_prefix_sum(T local) const {
    T before = 0;
    MPI_Exscan(&local, &before, 1, detail::mpi_type<T>(), MPI_SUM, comm_);
    return rank_ == 0 ? T(0) : before;
  }

  // Stops every process together when one of them has failed: `error` is this process's message
  // (empty when it has none). If any process has one, every process throws an Error with the
  // message of the lowest such rank, prefixed by that rank, so that no process waits forever
  // in a collective call the failed one will not make.
  void throw_if_any_failed(const std::string& error) const {
    const int failed = max(error.empty() ? -1 : size_ - rank_);  // the lowest failing rank wins
    if (failed < 0) return;
    const int root = size_ - failed;
    std::uint64_t length = rank_ == root ? error.size() : 0;
    MPI_Bcast(&length, 1, MPI_UINT64_T, root, comm_);
    std::string message = rank_ == root ? error : std::string(length, ' ');
    MPI_Bcast(message.data(), static_cast<int>(length), MPI_CHAR, root, comm_);
    throw Error("rank " + std::to_string(root) + ": " + message);
  }

 private:
  template <class T>
  T reduce(T local, MPI_Op op) const {
    T out{};
    MPI_Allreduce(&local, &out, 1, detail::mpi_type<T>(), op, comm_);
    return out;
  }
  template <class T>
  void reduce_in_place(std::vector<T>& values, MPI_Op op) const {
    MPI_Allreduce(MPI_IN_PLACE, values.data(), static_cast<int>(values.size()), detail::mpi_type<T>(), op, comm_);
  }

  MPI_Comm comm_;
  int rank_ = 0, size_ = 1;
};

}  // namespace MPSFSI_ABI
}  // namespace mpsfsi
