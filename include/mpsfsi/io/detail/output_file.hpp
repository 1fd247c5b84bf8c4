// SPDX-License-Identifier: BSD-3-Clause
#pragma once

#include <cerrno>
#include <cstddef>
#include <cstdio>
#include <memory>
#include <string>
#include <string_view>
#include <system_error>
#include <utility>

#include "mpsfsi/core/abi.hpp"
#include "mpsfsi/core/error.hpp"

// File plumbing shared by the writers: C stdio rather than iostreams because fopen/fwrite set
// errno on POSIX, so an IoError can say *why* a path could not be written.
namespace mpsfsi {
inline namespace MPSFSI_ABI {
namespace detail {

// The OS's reason for errno value `err`; std::generic_category is thread-safe where strerror
// is not.
inline std::string os_reason(int err) {
  return err != 0 ? std::generic_category().message(err) : std::string("unknown reason");
}

[[noreturn]] inline void throw_io(const std::string& where, const std::string& what, int err) {
  throw IoError("mpsfsi::" + where + ": " + what + ": " + os_reason(err));
}

struct FileCloser {
  void operator()(std::FILE* f) const { std::fclose(f); }
};
using FilePtr = std::unique_ptr<std::FILE, FileCloser>;

inline FilePtr open_file(const std::string& where, const std::string& path, const char* mode) {
  errno = 0;
  FilePtr f(std::fopen(path.c_str(), mode));
  if (!f) throw_io(where, "cannot open '" + path + "' for writing", errno);
  return f;
}

inline void write_bytes(std::FILE* f, const void* data, std::size_t bytes, const std::string& where,
                        const std::string& path) {
  if (bytes == 0) return;
  errno = 0;
  if (std::fwrite(data, 1, bytes, f) != bytes)
    throw_io(where, "cannot write '" + path + "'", errno);  // e.g. disk full
}

inline void flush_file(std::FILE* f, const std::string& where, const std::string& path) {
  errno = 0;
  if (std::fflush(f) != 0) throw_io(where, "cannot write '" + path + "'", errno);
}

// Writes `path + ".tmp"` and renames it over `path` on commit(), so a run killed mid-write
// leaves the previous good file in place. rename() replaces atomically on POSIX. Without
// commit() (an exception, say) the destructor removes the partial temporary.
class AtomicFile {
 public:
  AtomicFile(std::string where, std::string path)
      : where_(std::move(where)), path_(std::move(path)), tmp_(path_ + ".tmp") {
    errno = 0;
    file_.reset(std::fopen(tmp_.c_str(), "wb"));
    if (!file_) throw_io(where_, "cannot write '" + path_ + "' (opening '" + tmp_ + "')", errno);
  }
  AtomicFile(const AtomicFile&) = delete;
  AtomicFile& operator=(const AtomicFile&) = delete;
  ~AtomicFile() {
    if (file_) {
      file_.reset();
      std::remove(tmp_.c_str());
    }
  }

  void write(const void* data, std::size_t bytes) {
    write_bytes(file_.get(), data, bytes, where_, tmp_);
  }
  void write(std::string_view s) { write(s.data(), s.size()); }

  void commit() {
    flush_file(file_.get(), where_, tmp_);
    errno = 0;
    // fclose can report a deferred write error (NFS, quota), so it is checked, not left to RAII.
    const int closed = std::fclose(file_.release());
    if (closed != 0) {
      const int err = errno;
      std::remove(tmp_.c_str());
      throw_io(where_, "cannot write '" + tmp_ + "'", err);
    }
#if defined(_WIN32)
    // Windows' rename refuses to replace an existing file; this fallback is not atomic.
    std::remove(path_.c_str());
#endif
    errno = 0;
    if (std::rename(tmp_.c_str(), path_.c_str()) != 0) {
      const int err = errno;
      std::remove(tmp_.c_str());
      throw_io(where_, "cannot rename '" + tmp_ + "' to '" + path_ + "'", err);
    }
  }

 private:
  std::string where_;
  std::string path_;
  std::string tmp_;
  FilePtr file_;
};

// Escapes the five XML special characters, for field and file names inside attributes.
inline std::string xml_escape(std::string_view s) {
  std::string out;
  out.reserve(s.size());
  for (const char c : s) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      case '\'': out += "&apos;"; break;
      default: out += c;
    }
  }
  return out;
}

}  // namespace detail
}  // namespace MPSFSI_ABI
}  // namespace mpsfsi
