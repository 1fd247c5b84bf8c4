// SPDX-License-Identifier: BSD-3-Clause
#pragma once

#include <array>
#include <cerrno>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <string>
#include <tuple>
#include <type_traits>
#include <typeinfo>
#include <vector>

#include "mpsfsi/core/abi.hpp"
#include "mpsfsi/core/detail/state_archive.hpp"
#include "mpsfsi/core/error.hpp"
#include "mpsfsi/core/types.hpp"
#include "mpsfsi/io/detail/output_file.hpp"

#if defined(__GNUG__)
#include <cxxabi.h>

#include <cstdlib>
#endif

// Checkpoints: everything a solver's next step depends on, written so that a run continued from
// one gives the same bits as the run that wrote it (docs/design.md, "Checkpoints").
//
// A solver takes part by a member `template <class Archive> void checkpoint_state(Archive& a)`
// that passes each piece of its state to `a.value(x)` (one trivially copyable value),
// `a.array(v)` (a std::vector of them) or `a.label(s)` (a name that must match on reading, such
// as an output field's); the same function writes (the archive reads the members) and reads
// (the archive overwrites them). `checkpoint_particle_count()` gives the header's particle count
// and `checkpoint_restored()` rebuilds what is derived after a read.
//
// The file (numbers in the writing machine's byte order, which the header records through a
// known value):
//   "MPSFSICP"  format version (u32)  header size (u64)  header  payload size (u64)  payload
//   CRC-32 of header and payload (u32)
// The header: byte-order mark (u32 0x01020304), solver kind, dimension (u32), scalar type name,
// the solver's full type (its policy bundle: typeid name), particle count (u64). The file is
// written to `path.tmp` and renamed over `path` (detail::AtomicFile), so a run killed while
// writing leaves the previous checkpoint intact.
namespace mpsfsi {
inline namespace MPSFSI_ABI {

inline constexpr std::uint32_t checkpoint_format_version = 5;
inline constexpr std::uint32_t oldest_readable_checkpoint_format = 5;

namespace detail {

inline std::uint32_t crc32_update(std::uint32_t crc, const unsigned char* data, std::size_t n) {
  // CRC-32 (IEEE 802.3, reflected polynomial 0xEDB88320), as zlib and PNG compute it.
  static const std::array<std::uint32_t, 256> table = [] {
    std::array<std::uint32_t, 256> t{};
    for (std::uint32_t i = 0; i < 256; ++i) {
      std::uint32_t c = i;
      for (int k = 0; k < 8; ++k) c = (c & 1) ? 0xEDB88320u ^ (c >> 1) : c >> 1;
      t[i] = c;
    }
    return t;
  }();
  crc = ~crc;
  for (std::size_t i = 0; i < n; ++i) crc = table[(crc ^ data[i]) & 0xFFu] ^ (crc >> 8);
  return ~crc;
}

inline std::string readable_type_name(const char* mangled) {
#if defined(__GNUG__)
  int status = 0;
  char* name = abi::__cxa_demangle(mangled, nullptr, nullptr, &status);
  if (status == 0 && name) {
    std::string out(name);
    std::free(name);
    return out;
  }
#endif
  return mangled;
}

inline constexpr char checkpoint_magic[8] = {'M', 'P', 'S', 'F', 'S', 'I', 'C', 'P'};
inline constexpr std::uint32_t checkpoint_byte_order = 0x01020304u;

template <class Solver>
void checkpoint_header(CheckpointWriter& h, Solver& solver) {
  h.value(checkpoint_byte_order);
  h.label(Solver::checkpoint_kind);
  h.value(static_cast<std::uint32_t>(Solver::dimension));
  h.label(readable_type_name(typeid(typename Solver::scalar_type).name()));
  h.label(readable_type_name(typeid(Solver).name()));
  h.value(static_cast<std::uint64_t>(solver.checkpoint_particle_count()));
}

inline std::vector<unsigned char> read_whole_file(const std::string& path) {
  errno = 0;
  FilePtr f(std::fopen(path.c_str(), "rb"));
  if (!f) throw_io("read_checkpoint", "cannot open '" + path + "'", errno);
  std::vector<unsigned char> bytes;
  unsigned char buffer[1 << 16];
  for (;;) {
    const std::size_t got = std::fread(buffer, 1, sizeof buffer, f.get());
    bytes.insert(bytes.end(), buffer, buffer + got);
    if (got < sizeof buffer) break;
  }
  if (std::ferror(f.get())) throw_io("read_checkpoint", "cannot read '" + path + "'", errno);
  return bytes;
}

}  // namespace detail

// Writes the solver's state to `path` (via `path.tmp`, renamed when complete), followed by the
// state of any further objects with a checkpoint_state member (a program's own counters, say).
// Throws IoError if the file cannot be written; the previous file at `path`, if any, is then
// untouched.
template <class Solver, class... Extra>
void write_checkpoint(const std::string& path, Solver& solver, Extra&... extra) {
  detail::CheckpointWriter header, payload;
  detail::checkpoint_header(header, solver);
  solver.checkpoint_state(payload);
  (extra.checkpoint_state(payload), ...);
  std::uint32_t crc = detail::crc32_update(0, header.bytes().data(), header.bytes().size());
  crc = detail::crc32_update(crc, payload.bytes().data(), payload.bytes().size());
  const std::uint32_t version = checkpoint_format_version;
  const std::uint64_t header_size = header.bytes().size(), payload_size = payload.bytes().size();
  detail::AtomicFile file("write_checkpoint", path);
  file.write(detail::checkpoint_magic, sizeof detail::checkpoint_magic);
  file.write(&version, sizeof version);
  file.write(&header_size, sizeof header_size);
  file.write(header.bytes().data(), header.bytes().size());
  file.write(&payload_size, sizeof payload_size);
  file.write(payload.bytes().data(), payload.bytes().size());
  file.write(&crc, sizeof crc);
  file.commit();
}

// Restores the solver's state from `path`. The solver must be built as the one that wrote it
// (same kind, dimension, scalar type, policy bundle, particle count and fields); anything else,
// and a truncated, corrupted or newer-format file, is an InvalidInput naming what does not
// match. IoError if the file cannot be read. The solver (and the further objects, read in the
// order write_checkpoint was given them) are changed only once every check has passed and the
// whole payload has been read.
template <class Solver, class... Extra>
void read_checkpoint(const std::string& path, Solver& solver, Extra&... extra) {
  const std::vector<unsigned char> bytes = detail::read_whole_file(path);
  detail::CheckpointReader file(bytes.data(), bytes.size(), path);
  char magic[sizeof detail::checkpoint_magic] = {};
  if (bytes.size() < sizeof magic || std::memcmp(bytes.data(), detail::checkpoint_magic, sizeof magic) != 0)
    detail::throw_invalid("read_checkpoint", "'" + path + "' is not an mpsfsi checkpoint");
  for (char& c : magic) file.value(c);
  std::uint32_t version = 0;
  file.value(version);
  if (version > checkpoint_format_version)
    detail::throw_invalid("read_checkpoint", "'" + path + "' has format version " + std::to_string(version) +
                                                 "; this build reads versions up to " +
                                                 std::to_string(checkpoint_format_version));
  if (version == 0) file.corrupt("format version 0");
  if (version < oldest_readable_checkpoint_format)
    detail::throw_invalid("read_checkpoint", "'" + path + "' has format version " + std::to_string(version) +
                                                 ", older than this build reads (" +
                                                 std::to_string(oldest_readable_checkpoint_format) + " to " +
                                                 std::to_string(checkpoint_format_version) + ")");
  std::uint64_t header_size = 0;
  file.value(header_size);
  const std::size_t header_at = sizeof magic + sizeof version + sizeof header_size;
  if (header_size > bytes.size() - header_at) file.corrupt("it ends inside the header");
  const std::size_t payload_size_at = header_at + static_cast<std::size_t>(header_size);
  if (bytes.size() - payload_size_at < sizeof(std::uint64_t)) file.corrupt("it ends after the header");
  std::uint64_t payload_size = 0;
  std::memcpy(&payload_size, bytes.data() + payload_size_at, sizeof payload_size);
  const std::size_t payload_at = payload_size_at + sizeof payload_size;
  const std::size_t expected = bytes.size() - payload_at;
  if (payload_size > expected || expected - payload_size != sizeof(std::uint32_t))
    file.corrupt("it has " + std::to_string(bytes.size()) + " bytes, its header announces " +
                 std::to_string(payload_at + payload_size + sizeof(std::uint32_t)) + " (truncated?)");
  std::uint32_t stored_crc = 0;
  std::memcpy(&stored_crc, bytes.data() + payload_at + payload_size, sizeof stored_crc);
  std::uint32_t crc = detail::crc32_update(0, bytes.data() + header_at, static_cast<std::size_t>(header_size));
  crc = detail::crc32_update(crc, bytes.data() + payload_at, static_cast<std::size_t>(payload_size));
  if (crc != stored_crc) file.corrupt("its checksum does not match its contents");

  // The header against this solver.
  detail::CheckpointReader header(bytes.data() + header_at, static_cast<std::size_t>(header_size), path);
  std::uint32_t order = 0;
  header.value(order);
  if (order != detail::checkpoint_byte_order)
    detail::throw_invalid("read_checkpoint", "'" + path + "' was written on a machine of the other byte order");
  const auto mismatch = [&](const std::string& file_has, const std::string& solver_has) {
    detail::throw_invalid("read_checkpoint", "'" + path + "' holds " + file_has + ", this solver " + solver_has);
  };
  if (const std::string kind = header.text(); kind != Solver::checkpoint_kind)
    mismatch(kind + " state", std::string("is a ") + Solver::checkpoint_kind);
  std::uint32_t dimension = 0;
  header.value(dimension);
  if (dimension != static_cast<std::uint32_t>(Solver::dimension))
    mismatch("a " + std::to_string(dimension) + "D state", "is " + std::to_string(Solver::dimension) + "D");
  const std::string scalar = detail::readable_type_name(typeid(typename Solver::scalar_type).name());
  if (const std::string s = header.text(); s != scalar) mismatch("scalar type " + s, "uses " + scalar);
  const std::string type = detail::readable_type_name(typeid(Solver).name());
  if (const std::string t = header.text(); t != type)
    mismatch("the state of " + t, "is " + type + " (another policy bundle)");
  std::uint64_t particles = 0;
  header.value(particles);
  if (particles != solver.checkpoint_particle_count())
    mismatch(std::to_string(particles) + " particles", "has " + std::to_string(solver.checkpoint_particle_count()));

  // Read into a copy, so that a payload that does not fit leaves the solver as it was.
  Solver restored = solver;
  std::tuple<Extra...> restored_extra(extra...);
  detail::CheckpointReader payload(bytes.data() + payload_at, static_cast<std::size_t>(payload_size), path);
  restored.checkpoint_state(payload);
  std::apply([&payload](auto&... e) { (e.checkpoint_state(payload), ...); }, restored_extra);
  if (!payload.at_end()) payload.corrupt("data left over after the state it holds");
  restored.checkpoint_restored();
  solver = std::move(restored);
  std::tie(extra...) = std::move(restored_extra);
}

}  // namespace MPSFSI_ABI
}  // namespace mpsfsi
