// SPDX-License-Identifier: BSD-3-Clause
#include "mpsfsi/io/csv_writer.hpp"

#include <doctest/doctest.h>

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <limits>
#include <sstream>
#include <string>
#include <system_error>
#include <vector>

namespace {

std::vector<std::string> read_lines(const std::string& path) {
  std::ifstream in(path);
  REQUIRE(in);
  std::vector<std::string> lines;
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

std::vector<double> parse_row(const std::string& line) {
  std::vector<double> out;
  std::istringstream in(line);
  for (std::string cell; std::getline(in, cell, ',');) out.push_back(std::strtod(cell.c_str(), nullptr));
  return out;
}

}  // namespace

TEST_SUITE("io") {

TEST_CASE("io.csv: header and values round-trip exactly, each row on disk at once") {
  const std::string path = "io_csv_roundtrip.csv";
  mpsfsi::CsvWriter csv(path, {"t", "tip x", "energy"});
  CHECK(read_lines(path) == std::vector<std::string>{"t,tip x,energy"});

  const std::vector<std::vector<double>> rows = {
      {0.0, 0.1, 1.0 / 3.0},
      {1e-300, -2.5, std::numeric_limits<double>::max()},
      {std::numeric_limits<double>::denorm_min(), 123456789.0123456789, -0.0}};
  csv.row({rows[0][0], rows[0][1], rows[0][2]});
  CHECK(read_lines(path).size() == 2);  // flushed: readable while the writer is alive
  csv.row(rows[1]);
  csv.row(rows[2]);

  const auto lines = read_lines(path);
  REQUIRE(lines.size() == 4);
  for (std::size_t r = 0; r < rows.size(); ++r) {
    const auto got = parse_row(lines[r + 1]);
    REQUIRE(got.size() == 3);
    for (std::size_t c = 0; c < 3; ++c) {
      CHECK(got[c] == rows[r][c]);
      CHECK(std::signbit(got[c]) == std::signbit(rows[r][c]));
    }
  }
}

TEST_CASE("io.csv: column names needing quotes follow RFC 4180") {
  const std::string path = "io_csv_quotes.csv";
  mpsfsi::CsvWriter csv(path, {"a,b", "say \"hi\"", "c"});
  csv.row({1, 2, 3});
  const auto lines = read_lines(path);
  REQUIRE(lines.size() == 2);
  CHECK(lines[0] == "\"a,b\",\"say \"\"hi\"\"\",c");
  CHECK(lines[1] == "1,2,3");
}

TEST_CASE("io.csv: a wrong column count throws InvalidInput and writes nothing") {
  const std::string path = "io_csv_count.csv";
  mpsfsi::CsvWriter csv(path, {"t", "x"});
  CHECK_THROWS_WITH_AS(csv.row({1.0}), doctest::Contains("got 1 values for 2 columns"),
                       mpsfsi::InvalidInput);
  CHECK_THROWS_AS(csv.row(std::vector<double>{1, 2, 3}), mpsfsi::InvalidInput);
  csv.row({0.5, 0.25});
  CHECK(read_lines(path) == std::vector<std::string>{"t,x", "0.5,0.25"});
  CHECK_THROWS_AS(mpsfsi::CsvWriter("io_csv_none.csv", {}), mpsfsi::InvalidInput);
}

TEST_CASE("io.csv: an unwritable path throws IoError with the path and the OS reason") {
  const std::string reason = std::generic_category().message(ENOENT);
  CHECK_THROWS_WITH_AS(mpsfsi::CsvWriter("/nonexistent_dir/h.csv", {"t"}),
                       doctest::Contains("'/nonexistent_dir/h.csv'"), mpsfsi::IoError);
  CHECK_THROWS_WITH_AS(mpsfsi::CsvWriter("/nonexistent_dir/h.csv", {"t"}),
                       doctest::Contains(reason.c_str()), mpsfsi::IoError);
}

// A run restarted from a checkpoint continues its CSV after the rows it had at the checkpoint;
// rows the stopped run wrote after it are dropped.
TEST_CASE("io.csv: continue_after keeps the header and the first rows, then appends") {
  const std::string path = "io_csv_continue.csv";
  {
    mpsfsi::CsvWriter csv(path, {"t", "x"});
    for (int k = 0; k < 5; ++k) csv.row({0.1 * k, 2.0 * k});
    CHECK(csv.rows() == 5);
  }
  {
    auto csv = mpsfsi::CsvWriter::continue_after(path, {"t", "x"}, 3);
    CHECK(csv.rows() == 3);
    csv.row({0.3, 99.0});
    CHECK(csv.rows() == 4);
  }
  const auto lines = read_lines(path);
  REQUIRE(lines.size() == 5);
  CHECK(lines[0] == "t,x");
  CHECK(parse_row(lines[3]) == std::vector<double>{0.2, 4.0});
  CHECK(parse_row(lines[4]) == std::vector<double>{0.3, 99.0});
  CHECK_THROWS_WITH_AS(mpsfsi::CsvWriter::continue_after(path, {"t", "y"}, 1), doctest::Contains("header t,y"),
                       mpsfsi::InvalidInput);
  CHECK_THROWS_WITH_AS(mpsfsi::CsvWriter::continue_after(path, {"t", "x"}, 9),
                       doctest::Contains("has 4 complete rows, not the 9"), mpsfsi::InvalidInput);
  CHECK_THROWS_AS(mpsfsi::CsvWriter::continue_after("io_csv_missing.csv", {"t"}, 0), mpsfsi::IoError);
}

}  // TEST_SUITE("io")
