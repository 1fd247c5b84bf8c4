// SPDX-License-Identifier: BSD-3-Clause
#pragma once

#include <cstddef>
#include <initializer_list>
#include <limits>
#include <locale>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "mpsfsi/core/error.hpp"
#include "mpsfsi/io/detail/output_file.hpp"

namespace mpsfsi {

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
    std::string header;
    for (std::size_t c = 0; c < columns_.size(); ++c) {
      if (c > 0) header += ',';
      header += quote(columns_[c]);
    }
    header += '\n';
    put(header);
    format_.imbue(std::locale::classic());  // a decimal comma would split the columns
    format_.precision(std::numeric_limits<double>::max_digits10);
  }

  // Throws InvalidInput if the number of values is not the number of columns.
  void row(std::initializer_list<double> values) { write_row(values.begin(), values.size()); }
  void row(const std::vector<double>& values) { write_row(values.data(), values.size()); }

  const std::string& path() const { return path_; }
  const std::vector<std::string>& columns() const { return columns_; }

 private:
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
};

}  // namespace mpsfsi
