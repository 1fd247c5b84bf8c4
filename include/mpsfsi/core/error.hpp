// SPDX-License-Identifier: BSD-3-Clause
#pragma once

#include <stdexcept>
#include <string>

#include "mpsfsi/core/abi.hpp"

namespace mpsfsi {
inline namespace MPSFSI_ABI {

// Base of every exception mpsfsi throws, so callers can catch the library's errors as one.
class Error : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Input that cannot be simulated: wrong sizes, non-finite values, non-positive lengths.
class InvalidInput : public Error {
 public:
  using Error::Error;
};

// A file could not be opened, written or parsed.
class IoError : public Error {
 public:
  using Error::Error;
};

// A run that became unphysical (non-finite or runaway values, a linear solve that did not
// converge). The state of the solver is left at the last good step.
class SimulationError : public Error {
 public:
  SimulationError(const std::string& what, long long step, double time, long long particle)
      : Error(what), step_(step), time_(time), particle_(particle) {}
  long long step() const { return step_; }
  double time() const { return time_; }
  long long particle() const { return particle_; }  // -1 when no single particle is to blame

 private:
  long long step_;
  double time_;
  long long particle_;
};

namespace detail {

[[noreturn]] inline void throw_invalid(const std::string& where, const std::string& what) {
  throw InvalidInput("mpsfsi::" + where + ": " + what);
}

}  // namespace detail
}  // namespace MPSFSI_ABI
}  // namespace mpsfsi
