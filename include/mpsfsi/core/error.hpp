// SPDX-License-Identifier: BSD-3-Clause
#pragma once

#include <stdexcept>
#include <string>

namespace mpsfsi {

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

namespace detail {

[[noreturn]] inline void throw_invalid(const std::string& where, const std::string& what) {
  throw InvalidInput("mpsfsi::" + where + ": " + what);
}

}  // namespace detail
}  // namespace mpsfsi
