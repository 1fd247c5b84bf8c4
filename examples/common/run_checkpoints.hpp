// SPDX-License-Identifier: BSD-3-Clause
// Checkpoints of a running example: at a simulated-time interval (--checkpoint-every) and when
// the run is asked to stop (Ctrl-C, SIGTERM), into <out>/<name>_<step>.bin (name "checkpoint"
// unless the example runs several cases into one folder; <name>_<step>_p<rank>.bin for each
// process of a distributed run), written by
// mpsfsi::write_checkpoint (a temporary file renamed when complete, so a kill at any moment
// leaves the previous checkpoint valid). --restart FILE continues a run from one.
#pragma once

#include <csignal>
#include <cstdio>
#include <string>

#include <mpsfsi/io/checkpoint.hpp>

namespace mpsfsi_examples {

namespace detail {
inline volatile std::sig_atomic_t stop_signal = 0;
inline void request_stop(int signal) { stop_signal = signal; }
}  // namespace detail

class RunCheckpoints {
 public:
  // every: simulated seconds between checkpoints (0: only when asked to stop). Installs the
  // SIGINT and SIGTERM handlers, which let the current step finish.
  // piece: appended to the file name before ".bin" (a distributed run's "_p<rank>").
  RunCheckpoints(std::string out, double every, std::string name = "checkpoint", std::string piece = "")
      : out_(std::move(out)), name_(std::move(name)), piece_(std::move(piece)), every_(every) {
    std::signal(SIGINT, detail::request_stop);
    std::signal(SIGTERM, detail::request_stop);
  }

  // Whether the run was asked to stop (then write() and leave the loop).
  bool stop_requested() const { return detail::stop_signal != 0; }
  // The exit code of a run stopped by a signal (128 + the signal's number, as shells report it).
  int stop_exit_code() const { return 128 + static_cast<int>(detail::stop_signal); }

  // Whether the interval has come round at simulated time t (the first one at t = every after
  // the start or restart time).
  bool due(double t) {
    if (every_ <= 0) return false;
    if (next_ < 0) next_ = every_ * (static_cast<long long>(t / every_ + 1e-9) + 1);
    return t >= next_ - 1e-12;
  }

  // Writes the solver and the example's own state (objects with checkpoint_state) to
  // <out>/<name>_<step>.bin and returns the path.
  template <class Solver, class... State>
  std::string write(Solver& solver, long long step, double t, State&... state) {
    char number[32];
    std::snprintf(number, sizeof number, "_%09lld", step);
    const std::string path = out_ + "/" + name_ + number + piece_ + ".bin";
    mpsfsi::write_checkpoint(path, solver, state...);
    if (every_ > 0)
      while (next_ <= t + 1e-12) next_ += every_;
    return path;
  }

 private:
  std::string out_, name_, piece_;
  double every_;
  double next_ = -1;
};

}  // namespace mpsfsi_examples
