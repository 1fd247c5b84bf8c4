// SPDX-License-Identifier: BSD-3-Clause
#include "mpsfsi/io/progress.hpp"

#include <doctest/doctest.h>

#include <algorithm>
#include <sstream>
#include <string>
#include <vector>

namespace {

std::vector<std::string> lines_of(const std::string& s) {
  std::vector<std::string> out;
  std::istringstream in(s);
  for (std::string line; std::getline(in, line);) out.push_back(line);
  return out;
}

bool contains(const std::string& s, const std::string& part) { return s.find(part) != std::string::npos; }

}  // namespace

TEST_SUITE("io") {

TEST_CASE("io.progress: line mode reports the first step, each interval and the final step") {
  double now = 100.0;  // a fake wall clock, in seconds
  std::ostringstream out;
  mpsfsi::ProgressReporter progress(1.0, 2.0, out, mpsfsi::ProgressMode::lines, [&now] { return now; });
  CHECK_FALSE(progress.terminal());

  CHECK(progress.update(0, 0.0));  // first: always
  now = 101.0;
  CHECK_FALSE(progress.update(1, 0.1));  // inside the interval
  now = 102.5;
  CHECK(progress.update(2, 0.25));
  now = 103.0;
  CHECK(progress.update(3, 1.0));  // final: always, though inside the interval
  now = 103.5;
  CHECK_FALSE(progress.update(4, 1.0));  // the final report is not repeated
  now = 104.0;
  progress.finish();
  progress.finish();  // once only

  const auto lines = lines_of(out.str());
  REQUIRE(lines.size() == 4);
  CHECK(out.str().find('\r') == std::string::npos);
  CHECK(contains(lines[0], "step 0"));
  CHECK(contains(lines[0], "t 0 / 1"));
  CHECK(contains(lines[0], "eta --"));  // no rate yet
  CHECK(contains(lines[1], "step 2"));
  CHECK(contains(lines[1], "t 0.25 / 1 (25.0%)"));
  CHECK(contains(lines[1], "wall 2.5s"));
  CHECK(contains(lines[1], "eta 7.5s"));  // 2.5 s per 0.25 simulated, 0.75 to go
  CHECK(contains(lines[2], "step 3"));
  CHECK(contains(lines[2], "(100.0%)"));
  CHECK(contains(lines[2], "eta 0.0s"));
  CHECK(contains(lines[3], "done: step 4"));
  CHECK(contains(lines[3], "wall 4.0s"));
  CHECK(contains(lines[3], "steps/s"));
}

TEST_CASE("io.progress: terminal mode redraws one line") {
  double now = 0.0;
  std::ostringstream out;
  mpsfsi::ProgressReporter progress(2.0, 1.0, out, mpsfsi::ProgressMode::terminal, [&now] { return now; });
  CHECK(progress.terminal());
  for (int step = 1; step <= 20; ++step) {
    now += 0.25;
    progress.update(step, 0.1 * step);
  }
  const std::string drawn = out.str();
  CHECK(std::count(drawn.begin(), drawn.end(), '\n') == 0);
  CHECK(std::count(drawn.begin(), drawn.end(), '\r') >= 5);
  progress.finish();
  const auto lines = lines_of(out.str());
  REQUIRE(lines.size() == 2);  // the last state, then the summary
  CHECK(contains(lines.back(), "done: step 20"));
}

TEST_CASE("io.progress: a string stream is not a terminal; bad arguments throw") {
  std::ostringstream out;
  CHECK_FALSE(mpsfsi::ProgressReporter(1.0, 2.0, out).terminal());
  CHECK_THROWS_AS(mpsfsi::ProgressReporter(0.0), mpsfsi::InvalidInput);
  CHECK_THROWS_AS(mpsfsi::ProgressReporter(1.0, -1.0), mpsfsi::InvalidInput);
  mpsfsi::ProgressReporter idle(1.0, 2.0, out, mpsfsi::ProgressMode::lines);
  idle.finish();
  CHECK(contains(out.str(), "done: no steps"));
}

TEST_CASE("io.progress: durations read as seconds, minutes and hours") {
  using mpsfsi::detail::format_duration;
  CHECK(format_duration(12.34) == "12.3s");
  CHECK(format_duration(245.0) == "4m05s");
  CHECK(format_duration(3723.0) == "1h02m03s");
  CHECK(format_duration(1e300) == ">100h");
  CHECK(format_duration(-1.0) == "--");
}

TEST_CASE("io.progress: a label prefixes every line, and the legend names every column") {
  double now = 0.0;
  std::ostringstream out;
  mpsfsi::ProgressReporter progress(1.0, 0.0, out, mpsfsi::ProgressMode::lines, [&now] { return now; });
  progress.set_label("case 02");
  progress.update(1, 0.5);
  now = 1.0;
  progress.update(2, 1.0);
  progress.finish();
  const auto lines = lines_of(out.str());
  REQUIRE(lines.size() == 3);
  for (const auto& line : lines) CHECK(line.rfind("case 02: ", 0) == 0);
  CHECK(contains(lines[2], "case 02: done: step 2"));
  const std::string legend = mpsfsi::ProgressReporter::legend();
  for (const char* column : {"step", "simulated time", "percent", "wall time", "eta"}) CHECK(contains(legend, column));
}

}  // TEST_SUITE("io")
