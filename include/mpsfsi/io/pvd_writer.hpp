// SPDX-License-Identifier: BSD-3-Clause
#pragma once

#include <cmath>
#include <cstddef>
#include <limits>
#include <locale>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "mpsfsi/core/abi.hpp"
#include "mpsfsi/core/error.hpp"
#include "mpsfsi/io/detail/output_file.hpp"

namespace mpsfsi {
inline namespace MPSFSI_ABI {

// "prefix_000042.vtu": zero-padded so that a directory listing sorts in time order. Numbers
// wider than `digits` are written in full.
inline std::string numbered_file_name(const std::string& prefix, std::size_t number,
                                      const std::string& extension = ".vtu", int digits = 6) {
  std::string n = std::to_string(number);
  if (digits > 0 && n.size() < static_cast<std::size_t>(digits))
    n.insert(0, static_cast<std::size_t>(digits) - n.size(), '0');
  return prefix + "_" + n + extension;
}

// A ParaView collection (.pvd) mapping simulated times to output files. The index is rewritten
// (through a temporary and a rename) on construction and after every add(), so it is complete
// and valid at any moment of a long run, including after a crash.
class PvdWriter {
 public:
  struct Entry {
    double time;
    std::string file;  // relative to the .pvd's directory
  };

  // Writes an empty collection at once, so a bad path fails before the run, not after its
  // first output. An existing file is replaced.
  explicit PvdWriter(std::string path) : path_(std::move(path)) { rewrite(); }

  // Records `file` (relative to the .pvd's directory, as ParaView resolves it) at `time`.
  // Throws InvalidInput for a non-finite time or an empty name, IoError if the index cannot be
  // written (the entry is then not kept).
  void add(double time, std::string file) {
    if (!std::isfinite(time)) detail::throw_invalid("PvdWriter::add", "time is not finite");
    if (file.empty()) detail::throw_invalid("PvdWriter::add", "file name is empty");
    std::ostringstream line;
    line.imbue(std::locale::classic());  // a decimal comma would make the XML unreadable
    line.precision(std::numeric_limits<double>::max_digits10);
    line << "    <DataSet timestep=\"" << time << "\" group=\"\" part=\"0\" file=\""
         << detail::xml_escape(file) << "\"/>\n";
    const std::size_t old = body_.size();
    body_ += line.str();
    try {
      rewrite();
    } catch (...) {
      body_.resize(old);
      throw;
    }
    entries_.push_back(Entry{time, std::move(file)});
  }

  const std::vector<Entry>& entries() const { return entries_; }
  const std::string& path() const { return path_; }

  // The .pvd's directory with a trailing separator ("" for the working directory): where the
  // data files go so that the relative names added here resolve.
  std::string directory() const {
    const std::size_t slash = path_.find_last_of(separators());
    return slash == std::string::npos ? std::string() : path_.substr(0, slash + 1);
  }
  // Path of a data file named `file` next to the .pvd, to pass to the data writer.
  std::string resolve(const std::string& file) const { return directory() + file; }

 private:
  static const char* separators() {
#if defined(_WIN32)
    return "/\\";
#else
    return "/";
#endif
  }

  void rewrite() const {
    detail::AtomicFile out("PvdWriter", path_);
    out.write("<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"0.1\">\n"
              "  <Collection>\n");
    out.write(body_);
    out.write("  </Collection>\n</VTKFile>\n");
    out.commit();
  }

  std::string path_;
  std::string body_;  // the formatted <DataSet> lines, so a rewrite does not reformat them
  std::vector<Entry> entries_;
};

}  // namespace MPSFSI_ABI
}  // namespace mpsfsi
