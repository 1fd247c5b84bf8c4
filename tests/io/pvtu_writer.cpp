// SPDX-License-Identifier: BSD-3-Clause
#include "mpsfsi/io/pvtu_writer.hpp"

#include <doctest/doctest.h>

#include <fstream>
#include <iterator>
#include <regex>
#include <string>
#include <vector>

#include "mpsfsi/core/particle_set.hpp"

using namespace mpsfsi;

namespace {

std::string read_text(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

// (type, name, components) of every array declared by `tag` in an XML header.
std::vector<std::string> declarations(const std::string& xml, const std::string& tag) {
  std::vector<std::string> out;
  const std::regex re("<" + tag + " type=\"([A-Za-z0-9]+)\"(?: Name=\"([^\"]*)\")? NumberOfComponents=\"([0-9]+)\"");
  for (auto it = std::sregex_iterator(xml.begin(), xml.end(), re); it != std::sregex_iterator(); ++it)
    out.push_back((*it)[1].str() + " " + (*it)[2].str() + " " + (*it)[3].str());
  return out;
}

}  // namespace

TEST_SUITE("io") {

TEST_CASE("io.pvtu: the index declares the arrays of its pieces and lists them") {
  ParticleSet<2> set;
  set.add(Vec<2>(0, 0));
  set.add(Vec<2>(1, 0), ParticleKind::wall);
  set.add_field<double>("pressure");
  set.add_field<Mat<2>>("stress");
  set.add_field<std::int32_t>("free_surface");
  const auto writer = particle_vtu_writer(set);
  writer.write("pvtu_piece_p0.vtu");
  write_pvtu("pvtu_test.pvtu", writer, {"pvtu_piece_p0.vtu", "pvtu_piece_p1.vtu"});
  const std::string piece = read_text("pvtu_piece_p0.vtu");
  const std::string index = read_text("pvtu_test.pvtu");
  // The piece's point arrays and points, in order, are the index's.
  const auto in_piece = declarations(piece.substr(0, piece.find("<AppendedData")), "DataArray");
  const auto in_index = declarations(index, "PDataArray");
  // velocity, kind, id, the 3 fields, the points; then the piece's 3 cell arrays.
  REQUIRE(in_piece.size() == 6 + 1 + 3);
  CHECK(in_index == std::vector<std::string>(in_piece.begin(), in_piece.begin() + 7));
  CHECK(in_index.back() == "Float64 Points 3");
  CHECK(index.find("<VTKFile type=\"PUnstructuredGrid\"") != std::string::npos);
  CHECK(index.find("<Piece Source=\"pvtu_piece_p0.vtu\"/>") != std::string::npos);
  CHECK(index.find("<Piece Source=\"pvtu_piece_p1.vtu\"/>") != std::string::npos);
  CHECK_THROWS_AS(write_pvtu("pvtu_empty.pvtu", writer, {}), InvalidInput);
  CHECK_THROWS_AS(write_pvtu("no_such_directory/x.pvtu", writer, {"a.vtu"}), IoError);
}

}  // TEST_SUITE
