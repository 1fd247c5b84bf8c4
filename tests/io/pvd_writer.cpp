// SPDX-License-Identifier: BSD-3-Clause
#include "mpsfsi/io/pvd_writer.hpp"

#include <doctest/doctest.h>

#include <cerrno>
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <limits>
#include <string>
#include <system_error>
#include <vector>

namespace {

std::string read_all(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  REQUIRE(in);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

std::string attribute(const std::string& tag, const std::string& key) {
  const std::string pattern = " " + key + "=\"";
  const std::size_t begin = tag.find(pattern) + pattern.size();
  return tag.substr(begin, tag.find('"', begin) - begin);
}

std::string xml_unescape(std::string s) {
  const std::pair<const char*, const char*> table[] = {
      {"&lt;", "<"}, {"&gt;", ">"}, {"&quot;", "\""}, {"&apos;", "'"}, {"&amp;", "&"}};
  for (const auto& [from, to] : table)
    for (std::size_t at = s.find(from); at != std::string::npos; at = s.find(from, at + 1))
      s.replace(at, std::string(from).size(), to);
  return s;
}

// Reads the <DataSet> entries of a .pvd back; checks the document is closed.
std::vector<mpsfsi::PvdWriter::Entry> parse_pvd(const std::string& path) {
  const std::string s = read_all(path);
  CHECK(s.find("<VTKFile type=\"Collection\"") != std::string::npos);
  const std::string tail = "  </Collection>\n</VTKFile>\n";
  REQUIRE(s.size() >= tail.size());
  CHECK(s.substr(s.size() - tail.size()) == tail);
  std::vector<mpsfsi::PvdWriter::Entry> out;
  for (std::size_t at = s.find("<DataSet"); at != std::string::npos; at = s.find("<DataSet", at + 1)) {
    const std::string tag = s.substr(at, s.find("/>", at) - at);
    out.push_back({std::strtod(attribute(tag, "timestep").c_str(), nullptr),
                   xml_unescape(attribute(tag, "file"))});
  }
  return out;
}

}  // namespace

TEST_SUITE("io") {

TEST_CASE("io.pvd: numbered_file_name pads the number") {
  CHECK(mpsfsi::numbered_file_name("dam", 42) == "dam_000042.vtu");
  CHECK(mpsfsi::numbered_file_name("dam", 0, ".vtu", 3) == "dam_000.vtu");
  CHECK(mpsfsi::numbered_file_name("dam", 12345678) == "dam_12345678.vtu");
  CHECK(mpsfsi::numbered_file_name("out/beam", 7, ".csv", 2) == "out/beam_07.csv");
}

TEST_CASE("io.pvd: the index is valid after construction and after every add") {
  using mpsfsi::PvdWriter;
  const std::string path = "io_pvd_index.pvd";
  PvdWriter pvd(path);
  CHECK(parse_pvd(path).empty());

  const std::vector<PvdWriter::Entry> want = {
      {0.0, "run_000000.vtu"}, {1.0 / 3.0, "run_000001.vtu"}, {2.5e-7, "a&b <c>.vtu"},
      {-0.0, "x\"y'.vtu"}, {std::numeric_limits<double>::max(), "z.vtu"}};
  for (std::size_t k = 0; k < want.size(); ++k) {
    pvd.add(want[k].time, want[k].file);
    const auto got = parse_pvd(path);
    REQUIRE(got.size() == k + 1);
    for (std::size_t j = 0; j <= k; ++j) {
      CHECK(got[j].time == want[j].time);  // exact: written with max_digits10
      CHECK(got[j].file == want[j].file);
    }
    std::ifstream tmp(path + ".tmp");
    CHECK_FALSE(tmp.good());
  }
  CHECK(pvd.entries().size() == want.size());
  CHECK(pvd.entries()[2].file == "a&b <c>.vtu");
}

TEST_CASE("io.pvd: directory and resolve place data files next to the index") {
  CHECK(mpsfsi::PvdWriter("io_pvd_here.pvd").directory().empty());
  const mpsfsi::PvdWriter here("io_pvd_here.pvd");
  CHECK(here.resolve("a.vtu") == "a.vtu");
  const mpsfsi::PvdWriter dot("./io_pvd_dot.pvd");
  CHECK(dot.directory() == "./");
  CHECK(dot.resolve("a.vtu") == "./a.vtu");
}

TEST_CASE("io.pvd: bad input and unwritable paths throw") {
  using namespace mpsfsi;
  PvdWriter pvd("io_pvd_errors.pvd");
  CHECK_THROWS_AS(pvd.add(std::numeric_limits<double>::quiet_NaN(), "a.vtu"), InvalidInput);
  CHECK_THROWS_AS(pvd.add(std::numeric_limits<double>::infinity(), "a.vtu"), InvalidInput);
  CHECK_THROWS_AS(pvd.add(0.0, ""), InvalidInput);
  CHECK(pvd.entries().empty());
  CHECK(parse_pvd("io_pvd_errors.pvd").empty());

  const std::string reason = std::generic_category().message(ENOENT);
  CHECK_THROWS_WITH_AS(PvdWriter("/nonexistent_dir/run.pvd"),
                       doctest::Contains("'/nonexistent_dir/run.pvd'"), IoError);
  CHECK_THROWS_WITH_AS(PvdWriter("/nonexistent_dir/run.pvd"), doctest::Contains(reason.c_str()),
                       IoError);
}

}  // TEST_SUITE("io")
