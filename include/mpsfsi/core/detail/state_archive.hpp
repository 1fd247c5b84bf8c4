// SPDX-License-Identifier: BSD-3-Clause
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "mpsfsi/core/abi.hpp"
#include "mpsfsi/core/error.hpp"

// The archives of a solver's `checkpoint_state(Archive&)` (io/checkpoint.hpp describes the
// contract): a writer that serialises the state into bytes, a reader that puts it back, and a
// snapshot that keeps one state in memory to return to within a run.
namespace mpsfsi {
inline namespace MPSFSI_ABI {
namespace detail {

// Eigen's fixed-size vectors and matrices are contiguous arrays of their scalars.
template <class T, class = void>
struct is_fixed_eigen : std::false_type {};
template <class T>
struct is_fixed_eigen<T, std::void_t<decltype(T::SizeAtCompileTime), typename T::Scalar>>
    : std::bool_constant<(T::SizeAtCompileTime > 0) &&
                         sizeof(T) == static_cast<std::size_t>(T::SizeAtCompileTime) * sizeof(typename T::Scalar)> {};

template <class T>
inline constexpr bool is_raw_copyable = std::is_arithmetic_v<T> || std::is_enum_v<T> || is_fixed_eigen<T>::value;

// Serialises checkpoint_state() into a byte buffer.
class CheckpointWriter {
 public:
  template <class T>
  void value(const T& x) {
    static_assert(is_raw_copyable<T>, "mpsfsi checkpoint: value() takes arithmetic, enum or fixed-size Eigen types");
    append(&x, sizeof(T));
  }
  template <class T, class A>
  void array(const std::vector<T, A>& v) {
    static_assert(is_raw_copyable<T>, "mpsfsi checkpoint: array() takes vectors of arithmetic, enum or fixed-size Eigen types");
    value(static_cast<std::uint64_t>(v.size()));
    append(v.data(), v.size() * sizeof(T));
  }
  void label(const std::string& s) {
    value(static_cast<std::uint64_t>(s.size()));
    append(s.data(), s.size());
  }
  const std::vector<unsigned char>& bytes() const { return bytes_; }
  void clear() { bytes_.clear(); }  // keeps the capacity, so a reused writer allocates nothing

 private:
  void append(const void* p, std::size_t n) {
    const auto* c = static_cast<const unsigned char*>(p);
    bytes_.insert(bytes_.end(), c, c + n);
  }
  std::vector<unsigned char> bytes_;
};

// Reads checkpoint_state() back from a byte buffer; every read is bounds-checked.
class CheckpointReader {
 public:
  CheckpointReader(const unsigned char* data, std::size_t size, std::string path)
      : data_(data), size_(size), path_(std::move(path)) {}

  template <class T>
  void value(T& x) {
    static_assert(is_raw_copyable<T>, "mpsfsi checkpoint: value() takes arithmetic, enum or fixed-size Eigen types");
    take(&x, sizeof(T));
  }
  template <class T, class A>
  void array(std::vector<T, A>& v) {
    static_assert(is_raw_copyable<T>, "mpsfsi checkpoint: array() takes vectors of arithmetic, enum or fixed-size Eigen types");
    std::uint64_t n = 0;
    value(n);
    if (n > (size_ - at_) / (sizeof(T) ? sizeof(T) : 1)) corrupt("an array runs past the end of the data");
    v.resize(static_cast<std::size_t>(n));
    take(v.data(), v.size() * sizeof(T));
  }
  // Reads a label and checks it against the one this solver has.
  void label(const std::string& expected) {
    const std::string got = text();
    if (got != expected)
      throw_invalid("CheckpointReader", "'" + path_ + "' has '" + got + "' where this solver has '" + expected +
                                            "' (written by a solver with other fields or settings)");
  }
  std::string text() {
    std::uint64_t n = 0;
    value(n);
    if (n > size_ - at_) corrupt("a name runs past the end of the data");
    std::string s(reinterpret_cast<const char*>(data_ + at_), static_cast<std::size_t>(n));
    at_ += static_cast<std::size_t>(n);
    return s;
  }
  bool at_end() const { return at_ == size_; }
  [[noreturn]] void corrupt(const std::string& what) const {
    throw_invalid("CheckpointReader", "'" + path_ + "' is corrupt: " + what);
  }

 private:
  void take(void* p, std::size_t n) {
    if (n > size_ - at_) corrupt("it ends early");
    if (n) std::memcpy(p, data_ + at_, n);
    at_ += n;
  }
  const unsigned char* data_;
  std::size_t size_, at_ = 0;
  std::string path_;
};

// A solver's state kept in memory: the checkpoint's payload without file, header or checksum.
// An iterative coupling scheme returns both solvers to the start of the step with it; only what
// checkpoint_state lists is copied (positions, velocities, fields, bonds, time), not the
// neighbour lists, matrices and work arrays of the solver, which checkpoint_restored() rebuilds
// or the next step recomputes. A taken snapshot reuses its buffer and allocates nothing.
template <class S, class = void>
struct has_snapshot_restored : std::false_type {};
template <class S>
struct has_snapshot_restored<S, std::void_t<decltype(std::declval<S&>().snapshot_restored())>> : std::true_type {};

class StateSnapshot {
 public:
  template <class Solver>
  void take(Solver& solver) {
    writer_.clear();
    solver.checkpoint_state(writer_);
  }
  // Puts the state back, then calls the solver's snapshot_restored() if it has one (what a
  // return to its own earlier state needs rebuilt), checkpoint_restored() otherwise.
  template <class Solver>
  void restore(Solver& solver) const {
    CheckpointReader reader(writer_.bytes().data(), writer_.bytes().size(), "snapshot");
    solver.checkpoint_state(reader);
    if constexpr (has_snapshot_restored<Solver>::value)
      solver.snapshot_restored();
    else
      solver.checkpoint_restored();
  }
  bool empty() const { return writer_.bytes().empty(); }

 private:
  CheckpointWriter writer_;
};

}  // namespace detail
}  // namespace MPSFSI_ABI
}  // namespace mpsfsi
