// SPDX-License-Identifier: BSD-3-Clause
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <deque>
#include <string>
#include <tuple>
#include <type_traits>
#include <utility>
#include <variant>
#include <vector>

#include "mpsfsi/core/abi.hpp"
#include "mpsfsi/core/error.hpp"
#include "mpsfsi/core/particle_set.hpp"
#include "mpsfsi/core/types.hpp"
#include "mpsfsi/io/detail/output_file.hpp"

namespace mpsfsi {
inline namespace MPSFSI_ABI {

namespace detail {

// VTK reads raw binary in the byte order the file declares, so the host's order is declared
// rather than converting every value.
inline bool host_is_little_endian() {
  const std::uint16_t one = 1;
  unsigned char first = 0;
  std::memcpy(&first, &one, 1);
  return first == 1;
}

}  // namespace detail

// Writes particles as a VTK XML UnstructuredGrid (.vtu) with one VTK_VERTEX cell per particle,
// all data raw binary in <AppendedData> behind UInt64 byte counts (ParaView, VisIt and meshio
// read it). Points always have 3 components; 2D data is padded with zeros, vectors to 3 and
// tensors to 3x3 (9 components, row-major).
//
// Fields are views: an lvalue array must outlive write(), while an rvalue (a temporary computed
// just for output) is moved into the writer and kept there, so neither case copies or dangles.
template <int Dim, class Scalar = double>
class VtuWriter {
  static_assert(detail::is_supported_dim<Dim>, "mpsfsi::VtuWriter: Dim must be 2 or 3");
  static_assert(std::is_same_v<Scalar, float> || std::is_same_v<Scalar, double>,
                "mpsfsi::VtuWriter: Scalar must be float (Float32) or double (Float64)");

 public:
  using scalar_array = std::vector<Scalar>;
  using vector_array = VecArray<Dim, Scalar>;
  using tensor_array = MatArray<Dim, Scalar>;
  using int_array = std::vector<std::int32_t>;

  explicit VtuWriter(const vector_array& points) : points_(&points) {}
  explicit VtuWriter(vector_array&& points) : points_(&keep(std::move(points))) {}
  // Copying would leave views into the source's kept arrays; moving keeps them valid.
  VtuWriter(const VtuWriter&) = delete;
  VtuWriter& operator=(const VtuWriter&) = delete;
  VtuWriter(VtuWriter&&) = default;
  VtuWriter& operator=(VtuWriter&&) = default;

  std::size_t size() const { return points_->size(); }

  // The point arrays write() declares, in its order, as f(VTK type, name, components): what the
  // index of a parallel file (.pvtu, pvtu_writer.hpp) repeats for its pieces.
  template <class F>
  void for_each_declaration(F&& f) const {
    for (const Field& field : fields_)
      std::visit([&](auto* a) {
        using A = std::remove_const_t<std::remove_pointer_t<decltype(a)>>;
        f(type_name<element_t<A>>(), field.name, components<A>());
      }, field.data);
  }
  static const char* points_type() { return type_name<Scalar>(); }

  // Each add_* throws InvalidInput if the name is empty or taken, or the array's size is not
  // the point count. They return *this so calls can be chained.
  VtuWriter& add_scalar(std::string name, const scalar_array& v) { return add(std::move(name), &v); }
  VtuWriter& add_scalar(std::string name, scalar_array&& v) { return add(std::move(name), &keep(std::move(v))); }
  VtuWriter& add_vector(std::string name, const vector_array& v) { return add(std::move(name), &v); }
  VtuWriter& add_vector(std::string name, vector_array&& v) { return add(std::move(name), &keep(std::move(v))); }
  VtuWriter& add_tensor(std::string name, const tensor_array& v) { return add(std::move(name), &v); }
  VtuWriter& add_tensor(std::string name, tensor_array&& v) { return add(std::move(name), &keep(std::move(v))); }
  VtuWriter& add_int(std::string name, const int_array& v) { return add(std::move(name), &v); }
  VtuWriter& add_int(std::string name, int_array&& v) { return add(std::move(name), &keep(std::move(v))); }

  // Writes `path` via `path.tmp` and a rename, so an interrupted write never replaces a good
  // file with half of one. Throws IoError (path and OS reason) if the file cannot be written,
  // InvalidInput if a viewed array was resized after it was added.
  void write(const std::string& path) const {
    for (const Field& f : fields_) check_size(f.name, length(f.data), "write");
    const std::size_t n = size();

    std::string xml;
    std::uint64_t offset = 0;
    auto array_tag = [&](const char* type, const std::string& name, int comps, std::size_t elem) {
      xml += "        <DataArray type=\"" + std::string(type) + "\" Name=\"" + detail::xml_escape(name) +
             "\" NumberOfComponents=\"" + std::to_string(comps) +
             "\" format=\"appended\" offset=\"" + std::to_string(offset) + "\"/>\n";
      offset += sizeof(std::uint64_t) + std::uint64_t(n) * std::uint64_t(comps) * elem;
    };
    xml += "<?xml version=\"1.0\"?>\n<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"";
    xml += detail::host_is_little_endian() ? "LittleEndian" : "BigEndian";
    xml += "\" header_type=\"UInt64\">\n  <UnstructuredGrid>\n    <Piece NumberOfPoints=\"" +
           std::to_string(n) + "\" NumberOfCells=\"" + std::to_string(n) + "\">\n      <PointData>\n";
    for (const Field& f : fields_) {
      std::visit([&](auto* a) {
        using A = std::remove_const_t<std::remove_pointer_t<decltype(a)>>;
        using T = element_t<A>;
        array_tag(type_name<T>(), f.name, components<A>(), sizeof(T));
      }, f.data);
    }
    xml += "      </PointData>\n      <Points>\n";
    array_tag(type_name<Scalar>(), "Points", 3, sizeof(Scalar));
    xml += "      </Points>\n      <Cells>\n";
    array_tag("Int64", "connectivity", 1, sizeof(std::int64_t));
    array_tag("Int64", "offsets", 1, sizeof(std::int64_t));
    array_tag("UInt8", "types", 1, sizeof(std::uint8_t));
    xml += "      </Cells>\n    </Piece>\n  </UnstructuredGrid>\n  <AppendedData encoding=\"raw\">\n   _";

    detail::AtomicFile out("VtuWriter::write", path);
    out.write(xml);
    for (const Field& f : fields_) {
      std::visit([&](auto* a) { write_array(out, *a); }, f.data);
    }
    write_array(out, *points_);
    write_block<std::int64_t>(out, n, [](std::size_t i, auto& b) { b.push_back(std::int64_t(i)); });
    write_block<std::int64_t>(out, n, [](std::size_t i, auto& b) { b.push_back(std::int64_t(i) + 1); });
    write_block<std::uint8_t>(out, n, [](std::size_t, auto& b) { b.push_back(vtk_vertex); });
    out.write("\n  </AppendedData>\n</VTKFile>\n");
    out.commit();
  }

 private:
  static constexpr std::uint8_t vtk_vertex = 1;  // VTK's cell type id for a single point

  using FieldData = std::variant<const scalar_array*, const vector_array*, const tensor_array*,
                                 const int_array*>;
  struct Field {
    std::string name;
    FieldData data;
  };

  template <class A>
  const A& keep(A&& a) {
    // A deque never moves its elements on push_back, so views into it stay valid.
    auto& store = std::get<std::deque<A>>(kept_);
    store.push_back(std::move(a));
    return store.back();
  }

  template <class A>
  VtuWriter& add(std::string name, const A* a) {
    if (name.empty()) detail::throw_invalid("VtuWriter::add", "field name is empty");
    for (const Field& f : fields_)
      if (f.name == name) detail::throw_invalid("VtuWriter::add", "field '" + name + "' added twice");
    check_size(name, a->size(), "add");
    fields_.push_back(Field{std::move(name), a});
    return *this;
  }

  void check_size(const std::string& name, std::size_t got, const char* op) const {
    if (got != size())
      detail::throw_invalid(std::string("VtuWriter::") + op,
                            "field '" + name + "' has " + std::to_string(got) + " values for " +
                                std::to_string(size()) + " points");
  }

  static std::size_t length(const FieldData& d) {
    return std::visit([](auto* a) { return a->size(); }, d);
  }

  // The number type VTK sees: the array's own for scalars and ints, Scalar for vectors/tensors.
  template <class A>
  using element_t = std::conditional_t<std::is_arithmetic_v<typename A::value_type>,
                                       typename A::value_type, Scalar>;

  template <class T>
  static const char* type_name() {
    if constexpr (std::is_same_v<T, std::int32_t>) {
      return "Int32";
    } else if constexpr (std::is_same_v<T, float>) {
      return "Float32";
    } else {
      return "Float64";
    }
  }
  template <class A>
  static int components() {
    using T = typename A::value_type;
    if constexpr (std::is_arithmetic_v<T>) return 1;
    else if constexpr (T::ColsAtCompileTime == 1) return 3;
    else return 9;
  }

  // One appended block: the UInt64 byte count, then the values, staged in chunks so padding 2D
  // data needs no full-size copy.
  template <class T, class Fill>
  static void write_block(detail::AtomicFile& out, std::size_t tuples, int comps, Fill fill) {
    const std::uint64_t bytes = std::uint64_t(tuples) * std::uint64_t(comps) * sizeof(T);
    out.write(&bytes, sizeof bytes);
    constexpr std::size_t chunk = 4096;
    std::vector<T> buf;
    buf.reserve(std::min(tuples, chunk) * std::size_t(comps));
    for (std::size_t begin = 0; begin < tuples; begin += chunk) {
      buf.clear();
      const std::size_t end = std::min(tuples, begin + chunk);
      for (std::size_t i = begin; i < end; ++i) fill(i, buf);
      out.write(buf.data(), buf.size() * sizeof(T));
    }
  }
  template <class T, class Fill>
  static void write_block(detail::AtomicFile& out, std::size_t tuples, Fill fill) {
    write_block<T>(out, tuples, 1, fill);
  }

  template <class T>
  static void write_array(detail::AtomicFile& out, const std::vector<T>& a) {
    if constexpr (std::is_arithmetic_v<T>) {
      write_block<T>(out, a.size(), [&a](std::size_t i, auto& b) { b.push_back(a[i]); });
    } else if constexpr (T::ColsAtCompileTime == 1) {
      write_block<Scalar>(out, a.size(), 3, [&a](std::size_t i, auto& b) {
        for (int k = 0; k < 3; ++k) b.push_back(k < Dim ? a[i][k] : Scalar(0));
      });
    } else {
      write_block<Scalar>(out, a.size(), 9, [&a](std::size_t i, auto& b) {
        for (int r = 0; r < 3; ++r)
          for (int c = 0; c < 3; ++c) b.push_back(r < Dim && c < Dim ? a[i](r, c) : Scalar(0));
      });
    }
  }

  // Declared first: the rvalue constructor keeps its points here before points_ is set.
  std::tuple<std::deque<scalar_array>, std::deque<vector_array>, std::deque<tensor_array>,
             std::deque<int_array>>
      kept_;
  const vector_array* points_;
  std::vector<Field> fields_;
};

// A writer of a particle set: positions as points, then velocity, kind (Int32, the ParticleKind
// value), id, and every extra field under its own name. It views the set's arrays.
template <int Dim, class Scalar>
VtuWriter<Dim, Scalar> particle_vtu_writer(const ParticleSet<Dim, Scalar>& particles) {
  static_assert(std::is_same_v<Index, std::int32_t>, "ids are written as Int32");
  VtuWriter<Dim, Scalar> w(particles.positions());
  w.add_vector("velocity", particles.velocities());
  std::vector<std::int32_t> kind;
  kind.reserve(particles.kinds().size());
  for (const ParticleKind k : particles.kinds()) kind.push_back(static_cast<std::int32_t>(k));
  w.add_int("kind", std::move(kind));
  w.add_int("id", particles.ids());
  particles.for_each_scalar_field([&w](const std::string& name, const auto& a) { w.add_scalar(name, a); });
  particles.for_each_vector_field([&w](const std::string& name, const auto& a) { w.add_vector(name, a); });
  particles.for_each_tensor_field([&w](const std::string& name, const auto& a) { w.add_tensor(name, a); });
  particles.for_each_int_field([&w](const std::string& name, const auto& a) { w.add_int(name, a); });
  return w;
}

// Writes a particle set as particle_vtu_writer() lays it out.
template <int Dim, class Scalar>
void write_vtu(const std::string& path, const ParticleSet<Dim, Scalar>& particles) {
  particle_vtu_writer(particles).write(path);
}

}  // namespace MPSFSI_ABI
}  // namespace mpsfsi
