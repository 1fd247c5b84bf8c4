// SPDX-License-Identifier: BSD-3-Clause
#include "mpsfsi/io/vtu_writer.hpp"

#include <doctest/doctest.h>

#include <cerrno>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <iterator>
#include <random>
#include <sstream>
#include <string>
#include <system_error>
#include <vector>

namespace {

// A reader for exactly what VtuWriter produces, independent of it: it finds every DataArray
// in the XML header and cuts its bytes out of the raw appended section.
struct ParsedArray {
  std::string section, name, type;
  int components = 1;
  std::vector<char> bytes;
};

struct ParsedVtu {
  std::string byte_order, header_type;
  std::size_t points = 0, cells = 0;
  std::vector<ParsedArray> arrays;

  const ParsedArray& get(const std::string& section, const std::string& name) const {
    for (const auto& a : arrays)
      if (a.section == section && a.name == name) return a;
    FAIL("no array " << section << "/" << name);
    return arrays.front();
  }
};

std::string read_all(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  REQUIRE(in);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

bool file_exists(const std::string& path) { return std::ifstream(path).good(); }

std::string attribute(const std::string& tag, const std::string& key) {
  const std::string pattern = " " + key + "=\"";
  const std::size_t at = tag.find(pattern);
  if (at == std::string::npos) return "";
  const std::size_t begin = at + pattern.size();
  return tag.substr(begin, tag.find('"', begin) - begin);
}

std::uint64_t type_size(const std::string& type) {
  if (type == "Float64" || type == "Int64") return 8;
  if (type == "Float32" || type == "Int32") return 4;
  if (type == "UInt8") return 1;
  FAIL("unexpected DataArray type " << type);
  return 0;
}

ParsedVtu parse_vtu(const std::string& path) {
  const std::string s = read_all(path);
  const std::size_t appended = s.find("<AppendedData encoding=\"raw\">");
  REQUIRE(appended != std::string::npos);
  const std::size_t data = s.find('_', appended) + 1;
  ParsedVtu out;
  std::string section;
  std::uint64_t end_of_data = 0;
  for (std::size_t lt = s.find('<'); lt < appended; lt = s.find('<', lt + 1)) {
    const std::string tag = s.substr(lt, s.find('>', lt) - lt + 1);
    if (tag.rfind("<VTKFile", 0) == 0) {
      CHECK(attribute(tag, "type") == "UnstructuredGrid");
      out.byte_order = attribute(tag, "byte_order");
      out.header_type = attribute(tag, "header_type");
    } else if (tag.rfind("<Piece", 0) == 0) {
      out.points = std::stoul(attribute(tag, "NumberOfPoints"));
      out.cells = std::stoul(attribute(tag, "NumberOfCells"));
    } else if (tag == "<PointData>" || tag == "<Points>" || tag == "<Cells>") {
      section = tag.substr(1, tag.size() - 2);
    } else if (tag.rfind("<DataArray", 0) == 0) {
      ParsedArray a;
      a.section = section;
      a.name = attribute(tag, "Name");
      a.type = attribute(tag, "type");
      a.components = std::stoi(attribute(tag, "NumberOfComponents"));
      CHECK(attribute(tag, "format") == "appended");
      const std::uint64_t offset = std::stoull(attribute(tag, "offset"));
      std::uint64_t bytes = 0;
      REQUIRE(data + offset + sizeof bytes <= s.size());
      std::memcpy(&bytes, s.data() + data + offset, sizeof bytes);
      const std::size_t begin = data + offset + sizeof bytes;
      REQUIRE(begin + bytes <= s.size());
      a.bytes.assign(s.begin() + std::ptrdiff_t(begin), s.begin() + std::ptrdiff_t(begin + bytes));
      // Every array here has one tuple per point, so the byte count must match the XML's type.
      CHECK_MESSAGE(bytes == out.points * std::uint64_t(a.components) * type_size(a.type), a.name);
      end_of_data = std::max<std::uint64_t>(end_of_data, offset + sizeof bytes + bytes);
      out.arrays.push_back(std::move(a));
    }
  }
  // The arrays tile the appended section exactly, and the XML closes after it.
  CHECK(s.substr(data + end_of_data) == "\n  </AppendedData>\n</VTKFile>\n");
  return out;
}

template <class T>
std::vector<T> values_of(const ParsedArray& a) {
  REQUIRE(a.bytes.size() % sizeof(T) == 0);
  std::vector<T> v(a.bytes.size() / sizeof(T));
  std::memcpy(v.data(), a.bytes.data(), a.bytes.size());
  return v;
}

// Bitwise equality: the writer must not round, and -0.0 must stay -0.0.
template <class T>
bool same_bits(const std::vector<T>& a, const std::vector<T>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0;
}

template <int Dim, class Scalar>
std::vector<Scalar> padded(const mpsfsi::VecArray<Dim, Scalar>& v) {
  std::vector<Scalar> out;
  for (const auto& x : v)
    for (int k = 0; k < 3; ++k) out.push_back(k < Dim ? x[k] : Scalar(0));
  return out;
}

template <int Dim, class Scalar>
std::vector<Scalar> padded(const mpsfsi::MatArray<Dim, Scalar>& v) {
  std::vector<Scalar> out;
  for (const auto& m : v)
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) out.push_back(r < Dim && c < Dim ? m(r, c) : Scalar(0));
  return out;
}

template <int D, class S>
struct Case {
  static constexpr int dim = D;
  using scalar = S;
};

template <class S>
const char* float_type() {
  return sizeof(S) == 8 ? "Float64" : "Float32";
}

}  // namespace

TEST_SUITE("io") {

TEST_CASE_TEMPLATE("io.vtu: write_vtu round-trips points and every field bit for bit", C,
                   Case<2, double>, Case<3, double>, Case<2, float>, Case<3, float>) {
  constexpr int Dim = C::dim;
  using S = typename C::scalar;
  using namespace mpsfsi;
  const std::size_t n = 37;
  std::mt19937 rng(42);
  std::uniform_real_distribution<S> u(S(-10), S(10));
  ParticleSet<Dim, S> ps;
  for (std::size_t i = 0; i < n; ++i) {
    Vec<Dim, S> x, v;
    for (int k = 0; k < Dim; ++k) {
      x[k] = u(rng);
      v[k] = u(rng);
    }
    ps.add(x, static_cast<ParticleKind>(i % 4), v);
  }
  ps.positions()[0][0] = S(-0.0);
  auto p = ps.template add_field<S>("pressure");
  auto g = ps.template add_field<Vec<Dim, S>>("grad p");
  auto sigma = ps.template add_field<Mat<Dim, S>>("stress");
  auto body = ps.template add_field<std::int32_t>("body");
  for (std::size_t i = 0; i < n; ++i) {
    ps.field(p)[i] = u(rng) * S(1e3);
    ps.field(g)[i] = Vec<Dim, S>::Random();
    ps.field(sigma)[i] = Mat<Dim, S>::Random();
    ps.field(body)[i] = std::int32_t(i * 7919) - 100;
  }
  ps.permute([&] {  // ids then differ from indices, so the id field is really tested
    std::vector<Index> order(n);
    for (std::size_t k = 0; k < n; ++k) order[k] = Index((k * 5) % n);
    return order;
  }());
  const std::string path = "io_vtu_roundtrip_" + std::to_string(Dim) + "d_" + float_type<S>() + ".vtu";
  write_vtu(path, ps);
  CHECK_FALSE(file_exists(path + ".tmp"));

  const ParsedVtu f = parse_vtu(path);
  CHECK(f.header_type == "UInt64");
  CHECK(f.byte_order == "LittleEndian");  // every platform this is tested on
  CHECK(f.points == n);
  CHECK(f.cells == n);
  CHECK(f.arrays.size() == 3 + 4 + 1 + 3);  // built-in + extra point data, points, cells

  const ParsedArray& pts = f.get("Points", "Points");
  CHECK(pts.type == float_type<S>());
  CHECK(pts.components == 3);
  CHECK(same_bits(values_of<S>(pts), padded<Dim, S>(ps.positions())));

  const ParsedArray& vel = f.get("PointData", "velocity");
  CHECK(vel.type == float_type<S>());
  CHECK(vel.components == 3);
  CHECK(same_bits(values_of<S>(vel), padded<Dim, S>(ps.velocities())));

  const ParsedArray& kind = f.get("PointData", "kind");
  CHECK(kind.type == "Int32");
  std::vector<std::int32_t> kinds;
  for (auto k : ps.kinds()) kinds.push_back(std::int32_t(k));
  CHECK(same_bits(values_of<std::int32_t>(kind), kinds));
  CHECK(same_bits(values_of<std::int32_t>(f.get("PointData", "id")), ps.ids()));

  const ParsedArray& pa = f.get("PointData", "pressure");
  CHECK(pa.type == float_type<S>());
  CHECK(pa.components == 1);
  CHECK(same_bits(values_of<S>(pa), ps.field(p)));
  CHECK(f.get("PointData", "grad p").type == float_type<S>());
  CHECK(f.get("PointData", "grad p").components == 3);
  CHECK(same_bits(values_of<S>(f.get("PointData", "grad p")), padded<Dim, S>(ps.field(g))));
  CHECK(f.get("PointData", "stress").type == float_type<S>());
  CHECK(f.get("PointData", "stress").components == 9);
  CHECK(same_bits(values_of<S>(f.get("PointData", "stress")), padded<Dim, S>(ps.field(sigma))));
  CHECK(f.get("PointData", "body").type == "Int32");
  CHECK(same_bits(values_of<std::int32_t>(f.get("PointData", "body")), ps.field(body)));

  std::vector<std::int64_t> conn, offs;
  for (std::size_t i = 0; i < n; ++i) {
    conn.push_back(std::int64_t(i));
    offs.push_back(std::int64_t(i + 1));
  }
  CHECK(f.get("Cells", "connectivity").type == "Int64");
  CHECK(same_bits(values_of<std::int64_t>(f.get("Cells", "connectivity")), conn));
  CHECK(same_bits(values_of<std::int64_t>(f.get("Cells", "offsets")), offs));
  CHECK(same_bits(values_of<std::uint8_t>(f.get("Cells", "types")), std::vector<std::uint8_t>(n, 1)));
}

TEST_CASE("io.vtu: VtuWriter keeps temporaries, escapes names and writes empty sets") {
  using namespace mpsfsi;
  VecArray<3> pts = {Vec<3>(1, 2, 3), Vec<3>(4, 5, 6)};
  VtuWriter<3> w(pts);
  w.add_scalar("a<&>\"b", std::vector<double>{0.1, 1e-310}).add_int("i", std::vector<std::int32_t>{-1, 2});
  w.write("io_vtu_temporaries.vtu");
  const std::string text = read_all("io_vtu_temporaries.vtu");
  CHECK(text.find("Name=\"a&lt;&amp;&gt;&quot;b\"") != std::string::npos);
  const ParsedVtu f = parse_vtu("io_vtu_temporaries.vtu");
  CHECK(same_bits(values_of<double>(f.get("PointData", "a&lt;&amp;&gt;&quot;b")),
                  std::vector<double>{0.1, 1e-310}));
  CHECK(same_bits(values_of<std::int32_t>(f.get("PointData", "i")), std::vector<std::int32_t>{-1, 2}));

  // Moving a writer keeps the arrays it was given by rvalue reachable.
  VtuWriter<2> kept(VecArray<2>{Vec<2>(1, 2)});
  kept.add_vector("v", VecArray<2>{Vec<2>(3, 4)});
  VtuWriter<2> moved = std::move(kept);
  moved.write("io_vtu_moved.vtu");
  const ParsedVtu m = parse_vtu("io_vtu_moved.vtu");
  CHECK(same_bits(values_of<double>(m.get("Points", "Points")), std::vector<double>{1, 2, 0}));
  CHECK(same_bits(values_of<double>(m.get("PointData", "v")), std::vector<double>{3, 4, 0}));

  VtuWriter<2> empty(VecArray<2>{});
  empty.write("io_vtu_empty.vtu");
  const ParsedVtu e = parse_vtu("io_vtu_empty.vtu");
  CHECK(e.points == 0);
  CHECK(e.get("Points", "Points").bytes.empty());
}

TEST_CASE("io.vtu: size mismatches and duplicate names throw InvalidInput naming the field") {
  using namespace mpsfsi;
  VecArray<2> pts(4, Vec<2>::Zero());
  VtuWriter<2> w(pts);
  CHECK_THROWS_WITH_AS(w.add_scalar("pressure", std::vector<double>(3)),
                       doctest::Contains("'pressure' has 3 values for 4 points"), InvalidInput);
  CHECK_THROWS_WITH_AS(w.add_tensor("stress", MatArray<2>(5)), doctest::Contains("'stress'"),
                       InvalidInput);
  std::vector<double> p(4, 1.0);
  w.add_scalar("p", p);
  CHECK_THROWS_WITH_AS(w.add_scalar("p", p), doctest::Contains("'p' added twice"), InvalidInput);
  CHECK_THROWS_AS(w.add_int("", std::vector<std::int32_t>(4)), InvalidInput);

  // A viewed array resized after add() is caught at write(), before any file is touched.
  w.write("io_vtu_mismatch.vtu");
  const std::string good = read_all("io_vtu_mismatch.vtu");
  p.push_back(2.0);
  CHECK_THROWS_WITH_AS(w.write("io_vtu_mismatch.vtu"), doctest::Contains("'p' has 5 values"),
                       InvalidInput);
  CHECK(read_all("io_vtu_mismatch.vtu") == good);
}

TEST_CASE("io.vtu: an unwritable path throws IoError with the path and the OS reason") {
  using namespace mpsfsi;
  ParticleSet<3> ps(3);
  const std::string reason = std::generic_category().message(ENOENT);
  CHECK_THROWS_WITH_AS(write_vtu("/nonexistent_dir/x.vtu", ps),
                       doctest::Contains("'/nonexistent_dir/x.vtu'"), IoError);
  CHECK_THROWS_WITH_AS(write_vtu("/nonexistent_dir/x.vtu", ps), doctest::Contains(reason.c_str()),
                       IoError);
  // The library's errors can be caught as one type.
  CHECK_THROWS_AS(write_vtu("/nonexistent_dir/x.vtu", ps), Error);
}

}  // TEST_SUITE("io")
