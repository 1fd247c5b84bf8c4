// SPDX-License-Identifier: BSD-3-Clause
#pragma once

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <functional>
#include <iostream>
#include <locale>
#include <ostream>
#include <sstream>
#include <string>
#include <utility>

#include "mpsfsi/core/abi.hpp"
#include "mpsfsi/core/error.hpp"

#if __has_include(<unistd.h>)
#include <unistd.h>
#elif defined(_WIN32) && __has_include(<io.h>)
#include <io.h>
#endif

namespace mpsfsi {
inline namespace MPSFSI_ABI {

// How ProgressReporter draws: `automatic` redraws one line when the stream is std::cout,
// std::cerr or std::clog on a terminal and prints one line per report otherwise (log files,
// CI output, string streams); the other two force either behaviour.
enum class ProgressMode { automatic, terminal, lines };

namespace detail {

inline bool stream_is_terminal(const std::ostream& out) {
#if __has_include(<unistd.h>)
  if (&out == &std::cout) return ::isatty(STDOUT_FILENO) != 0;
  if (&out == &std::cerr || &out == &std::clog) return ::isatty(STDERR_FILENO) != 0;
#elif defined(_WIN32) && __has_include(<io.h>)
  if (&out == &std::cout) return ::_isatty(::_fileno(stdout)) != 0;
  if (&out == &std::cerr || &out == &std::clog) return ::_isatty(::_fileno(stderr)) != 0;
#else
  (void)out;
#endif
  return false;
}

// "12.3s", "4m05s", "1h02m03s"; "--" when unknown.
inline std::string format_duration(double seconds) {
  if (!std::isfinite(seconds) || seconds < 0) return "--";
  char buf[32];
  if (seconds < 60) {
    std::snprintf(buf, sizeof buf, "%.1fs", seconds);
    return buf;
  }
  if (seconds >= 360000) return ">100h";  // also keeps the integer conversion below in range
  const long long total = std::llround(seconds);
  const long long h = total / 3600, m = total % 3600 / 60, s = total % 60;
  if (h > 0) std::snprintf(buf, sizeof buf, "%lldh%02lldm%02llds", h, m, s);
  else std::snprintf(buf, sizeof buf, "%lldm%02llds", m, s);
  return buf;
}

inline double steady_seconds() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

}  // namespace detail

// Progress of a long run, printed at most once per wall-clock interval (and always at the first
// step and at the step that reaches the end time):
//   step 1200  t 0.12 / 2 (6.0%)  wall 1m23s  eta 21m40s
// The estimate extrapolates the simulated-time rate since the first update, so it tracks
// adaptive time steps rather than step counts.
class ProgressReporter {
 public:
  // Seconds since any fixed origin; injectable so tests need not sleep.
  using WallClock = std::function<double()>;

  // Throws InvalidInput unless end_time > 0 and interval_seconds >= 0, both finite.
  explicit ProgressReporter(double end_time, double interval_seconds = 2.0,
                            std::ostream& out = std::cerr,
                            ProgressMode mode = ProgressMode::automatic,
                            WallClock clock = detail::steady_seconds)
      : end_time_(end_time), interval_(interval_seconds), out_(&out), clock_(std::move(clock)) {
    if (!(std::isfinite(end_time) && end_time > 0))
      detail::throw_invalid("ProgressReporter", "end time must be finite and positive");
    if (!(std::isfinite(interval_seconds) && interval_seconds >= 0))
      detail::throw_invalid("ProgressReporter", "interval must be finite and non-negative");
    if (!clock_) detail::throw_invalid("ProgressReporter", "clock is empty");
    terminal_ = mode == ProgressMode::terminal ||
                (mode == ProgressMode::automatic && detail::stream_is_terminal(out));
    start_wall_ = clock_();
  }

  // Call once per step with the step number and the simulated time after it. Returns whether a
  // report was printed.
  bool update(std::int64_t step, double sim_time) {
    const double now = clock_();
    const bool first = !started_;
    if (first) {
      started_ = true;
      first_step_ = step;
      first_time_ = sim_time;
      first_wall_ = now;
    }
    last_step_ = step;
    last_time_ = sim_time;
    last_wall_ = now;
    const bool final = sim_time >= end_time_ && !final_printed_;
    if (!(first || final || now - last_print_ >= interval_)) return false;
    final_printed_ = final_printed_ || final;
    last_print_ = now;
    emit(report());
    return true;
  }

  // Prints the summary line (once): steps, simulated time, wall time and step rate.
  void finish() {
    if (finished_) return;
    finished_ = true;
    const double now = clock_();
    std::ostringstream s = stream();
    if (terminal_ && started_) {  // leave the last state on its own line above the summary
      const std::string line = report();
      s << '\r' << line << pad(line.size()) << '\n';
    }
    const double wall = now - start_wall_;
    s << label_ << "done: ";
    if (started_) {
      s << "step " << last_step_ << "  t " << last_time_ << " / " << end_time_ << "  wall "
        << detail::format_duration(wall);
      const double run_wall = last_wall_ - first_wall_;
      if (last_step_ > first_step_ && run_wall > 0) {
        s.precision(3);
        s << " (" << double(last_step_ - first_step_) / run_wall << " steps/s)";
      }
    } else {
      s << "no steps  wall " << detail::format_duration(wall);
    }
    s << '\n';
    *out_ << s.str() << std::flush;
  }

  bool terminal() const { return terminal_; }

  // A prefix for every line, naming what runs ("case 02: step 1200 ..."), when one program
  // reports several runs in turn.
  void set_label(std::string label) { label_ = label.empty() ? std::string() : std::move(label) + ": "; }

  // What the columns of a report mean, for a program to print once before its first run.
  static const char* legend() {
    return "progress: step number, simulated time t / end time (percent done), wall time since the start, "
           "estimated wall time left (eta)";
  }

 private:
  // Local formatting, so the caller's stream flags and locale are left as they were.
  static std::ostringstream stream() {
    std::ostringstream s;
    s.imbue(std::locale::classic());
    return s;
  }

  std::string report() const {
    std::ostringstream s = stream();
    const double percent = std::clamp(last_time_ / end_time_ * 100, 0.0, 100.0);
    s << label_ << "step " << last_step_ << "  t " << last_time_ << " / " << end_time_;
    s.precision(1);
    s << std::fixed << " (" << percent << "%)  wall "
      << detail::format_duration(last_wall_ - start_wall_) << "  eta ";
    const double done = last_time_ - first_time_;
    if (last_time_ >= end_time_) s << detail::format_duration(0);
    else if (done > 0) s << detail::format_duration((last_wall_ - first_wall_) / done * (end_time_ - last_time_));
    else s << "--";
    return s.str();
  }

  // Blanks left over from a longer previous line when redrawing in place.
  std::string pad(std::size_t length) const {
    return std::string(drawn_ > length ? drawn_ - length : 0, ' ');
  }

  void emit(const std::string& line) {
    if (terminal_) {
      *out_ << '\r' << line << pad(line.size()) << std::flush;
      drawn_ = line.size();
    } else {
      *out_ << line << '\n' << std::flush;  // flushed so `tail -f` on a log follows the run
    }
  }

  double end_time_;
  double interval_;
  std::ostream* out_;
  WallClock clock_;
  std::string label_;
  bool terminal_ = false;
  bool started_ = false;
  bool final_printed_ = false;
  bool finished_ = false;
  double start_wall_ = 0, first_wall_ = 0, last_wall_ = 0, last_print_ = 0;
  double first_time_ = 0, last_time_ = 0;
  std::int64_t first_step_ = 0, last_step_ = 0;
  std::size_t drawn_ = 0;
};

}  // namespace MPSFSI_ABI
}  // namespace mpsfsi
