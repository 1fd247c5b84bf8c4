// SPDX-License-Identifier: BSD-3-Clause
#pragma once

#include <cerrno>
#include <cstddef>
#include <cstdio>
#include <initializer_list>
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

// Time series as CSV: a header of column names, then one row of numbers per call. Values carry
// max_digits10 (17) significant digits so they read back bit for bit, and each row is flushed,
// so a run that dies keeps every row it wrote. Non-finite values appear as the C library prints
// them (nan, inf, -inf), which numpy and pandas read.
class CsvWriter {
 public:
  // Creates (or truncates) `path` and writes the header. Throws InvalidInput without columns,
  // IoError (path and OS reason) if the file cannot be written.
  CsvWriter(std::string path, std::vector<std::string> columns)
      : path_(std::move(path)), columns_(std::move(columns)) {
    if (columns_.empty()) detail::throw_invalid("CsvWriter", "no columns for '" + path_ + "'");
    file_ = detail::open_file("CsvWriter", path_, "w");
    put(header_line());
    set_format();
  }

  // Continues `path` after its first `rows` rows (a run restarted from a checkpoint that had
  // written that many): the header must be this writer's, later rows (written after the
  // checkpoint by the run that stopped) are dropped. InvalidInput if the header differs or the
  // file has fewer rows; IoError if it cannot be read or written.
  static CsvWriter continue_after(std::string path, std::vector<std::string> columns, std::size_t rows) {
    return CsvWriter(std::move(path), std::move(columns), rows);
  }

  // Rows written so far (rows kept by continue_after included).
  std::size_t rows() const { return rows_; }

  // Throws InvalidInput if the number of values is not the number of columns.
  void row(std::initializer_list<double> values) { write_row(values.begin(), values.size()); }
  void row(const std::vector<double>& values) { write_row(values.data(), values.size()); }

  const std::string& path() const { return path_; }
  const std::vector<std::string>& columns() const { return columns_; }

 private:
  CsvWriter(std::string path, std::vector<std::string> columns, std::size_t keep)
      : path_(std::move(path)), columns_(std::move(columns)) {
    if (columns_.empty()) detail::throw_invalid("CsvWriter", "no columns for '" + path_ + "'");
    std::string kept;
    {
      errno = 0;
      detail::FilePtr in(std::fopen(path_.c_str(), "rb"));
      if (!in) detail::throw_io("CsvWriter", "cannot open '" + path_ + "' to continue it", errno);
      char buffer[1 << 16];
      for (std::size_t got; (got = std::fread(buffer, 1, sizeof buffer, in.get())) > 0;) kept.append(buffer, got);
    }
    const std::string header = header_line();
    if (kept.compare(0, header.size(), header) != 0)
      detail::throw_invalid("CsvWriter", "'" + path_ + "' does not start with the header " + header.substr(0, header.size() - 1));
    std::size_t end = header.size();
    for (std::size_t r = 0; r < keep; ++r) {
      const std::size_t eol = kept.find('\n', end);
      if (eol == std::string::npos)
        detail::throw_invalid("CsvWriter", "'" + path_ + "' has " + std::to_string(r) + " complete rows, not the " +
                                               std::to_string(keep) + " to continue after");
      end = eol + 1;
    }
    kept.resize(end);
    file_ = detail::open_file("CsvWriter", path_, "w");
    put(kept);
    rows_ = keep;
    set_format();
  }

  std::string header_line() const {
    std::string header;
    for (std::size_t c = 0; c < columns_.size(); ++c) {
      if (c > 0) header += ',';
      header += quote(columns_[c]);
    }
    return header + '\n';
  }

  void set_format() {
    format_.imbue(std::locale::classic());  // a decimal comma would split the columns
    format_.precision(std::numeric_limits<double>::max_digits10);
  }

  void write_row(const double* v, std::size_t n) {
    if (n != columns_.size())
      detail::throw_invalid("CsvWriter::row", "got " + std::to_string(n) + " values for " +
                                                  std::to_string(columns_.size()) + " columns in '" +
                                                  path_ + "'");
    format_.str(std::string());
    for (std::size_t c = 0; c < n; ++c) {
      if (c > 0) format_ << ',';
      format_ << v[c];
    }
    format_ << '\n';
    put(format_.str());
    ++rows_;
  }

  void put(const std::string& s) {
    detail::write_bytes(file_.get(), s.data(), s.size(), "CsvWriter", path_);
    detail::flush_file(file_.get(), "CsvWriter", path_);
  }

  // RFC 4180: a name holding a comma, quote or line break is quoted, with quotes doubled.
  static std::string quote(const std::string& s) {
    if (s.find_first_of(",\"\r\n") == std::string::npos) return s;
    std::string out = "\"";
    for (const char ch : s) {
      if (ch == '"') out += '"';
      out += ch;
    }
    return out + '"';
  }

  std::string path_;
  std::vector<std::string> columns_;
  detail::FilePtr file_;
  std::ostringstream format_;
  std::size_t rows_ = 0;
};

}  // namespace MPSFSI_ABI
}  // namespace mpsfsi
