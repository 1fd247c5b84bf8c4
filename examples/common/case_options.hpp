// SPDX-License-Identifier: BSD-3-Clause
// The command line and the YAML case files of mpsfsi's examples (CLI11 and yaml-cpp: examples
// only, the library does not use them).
//
// Each option is bound to a variable of the example's own options struct and registered with
// its help text and unit, so `--help` lists every option with its default and unit. A case file
// (`--case-file case.yaml`) sets options by their long name without the dashes (`l0: 0.002`);
// options given on the command line override the file. `write_case` writes every option with
// the value the run uses (defaults resolved by the example included) as a case file that
// reruns it, and `--print-case` prints that file and stops before running anything.
//
// Bad input never reaches the run: a malformed number, a value outside an option's set, an
// unknown option, an unreadable or malformed case file, an unknown key or a value of the wrong
// type is one line on stderr naming the option or key, and exit code 2.
#pragma once

#include <charconv>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <functional>
#include <optional>
#include <set>
#include <stdexcept>
#include <string>
#include <system_error>
#include <type_traits>
#include <utility>
#include <vector>

#include <CLI/CLI.hpp>
#include <yaml-cpp/yaml.h>

namespace mpsfsi_examples {

// A bad command line or case file; what() is the one line the user sees.
class UsageError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

namespace detail {

// The shortest text that reads back as the same double (C++17 <charconv>).
inline std::string format_number(double v) {
  char buf[64];
  const auto r = std::to_chars(buf, buf + sizeof buf, v);
  return r.ec == std::errc() ? std::string(buf, r.ptr) : std::to_string(v);
}

template <class T>
std::string format_value(const T& v) {
  if constexpr (std::is_same_v<T, bool>) return v ? "true" : "false";
  else if constexpr (std::is_floating_point_v<T>) return format_number(static_cast<double>(v));
  else if constexpr (std::is_integral_v<T>) return std::to_string(v);
  else return v;
}

}  // namespace detail

// Values an option accepts, beyond its type: CLI11 validators with messages that read well.
inline CLI::Validator positive() {
  return CLI::Validator(
      [](std::string& s) -> std::string {
        double v = 0;
        return CLI::detail::lexical_cast(s, v) && v > 0 ? std::string() : "must be a positive number, not " + s;
      },
      "");
}
inline CLI::Validator non_negative() {
  return CLI::Validator(
      [](std::string& s) -> std::string {
        double v = 0;
        return CLI::detail::lexical_cast(s, v) && v >= 0 ? std::string() : "must be zero or positive, not " + s;
      },
      "");
}
inline CLI::Validator one_of(std::vector<std::string> values) {
  std::string list;
  for (const auto& v : values) list += (list.empty() ? "" : "|") + v;
  return CLI::Validator(
      [values, list](std::string& s) -> std::string {
        for (const auto& v : values)
          if (s == v) return {};
        return "must be one of " + list + ", not " + s;
      },
      "{" + list + "}");
}

class CaseOptions {
 public:
  CaseOptions(std::string program, std::string description)
      : program_(std::move(program)), app_(std::move(description), program_) {
    app_.option_defaults()->always_capture_default();
    app_.get_formatter()->column_width(34);
    app_.add_option("--case-file", case_file_, "YAML case file (keys: the long option names without dashes); "
                                               "options on the command line override it");
    app_.add_flag("--print-case", print_case_, "print the resolved case as YAML and exit without running");
  }

  // A value option bound to `value`; its current value is the default shown by --help. The unit
  // is printed after the help text. Floating-point values must be finite.
  template <class T>
  CLI::Option* add(const std::string& name, T& value, const std::string& help, const std::string& unit = "") {
    CLI::Option* opt = app_.add_option(name, value, unit.empty() ? help : help + " [" + unit + "]");
    if constexpr (std::is_floating_point_v<T>)
      opt->check(CLI::Validator(
          [](std::string& s) -> std::string {
            double v = 0;
            if (!CLI::detail::lexical_cast(s, v)) return "must be a number, not " + s;
            return std::isfinite(v) ? std::string() : "must be finite, not " + s;
          },
          ""));
    else if constexpr (std::is_integral_v<T>)
      opt->check(CLI::Validator(
          [](std::string& s) -> std::string {
            T v{};
            return CLI::detail::lexical_cast(s, v) ? std::string() : "must be a whole number, not " + s;
          },
          ""));
    entries_.push_back({opt, [&value] { return detail::format_value(value); }, std::is_same_v<T, std::string>});
    return opt;
  }

  // An on/off switch: `--name` on the command line, `name: true|false` in a case file.
  CLI::Option* flag(const std::string& name, bool& value, const std::string& help) {
    CLI::Option* opt = app_.add_flag(name, value, help);
    entries_.push_back({opt, [&value] { return detail::format_value(value); }, false});
    return opt;
  }

  CLI::App& app() { return app_; }

  // Parses the command line and, when given, the case file. Throws UsageError on bad input;
  // returns false after printing the help when --help was asked for.
  bool parse(int argc, const char* const* argv) {
    try {
      app_.parse(argc, argv);
    } catch (const CLI::CallForHelp&) {
      std::fputs(app_.help().c_str(), stdout);
      return false;
    } catch (const CLI::ExtrasError&) {
      throw UsageError("unknown option or stray argument: " + CLI::detail::join(app_.remaining(), " "));
    } catch (const CLI::ParseError& e) {
      throw UsageError(e.what());
    }
    if (!case_file_.empty()) apply_case_file(case_file_);
    return true;
  }

  // parse() for main(): returns the exit code when the program should stop (0 after --help, 2
  // after bad input, with its one-line message on stderr), or nothing to go on.
  std::optional<int> parse_or_exit_code(int argc, const char* const* argv) {
    try {
      return parse(argc, argv) ? std::nullopt : std::optional<int>(0);
    } catch (const UsageError& e) {
      std::fprintf(stderr, "%s: %s (see %s --help)\n", program_.c_str(), e.what(), program_.c_str());
      return 2;
    }
  }

  // Every option with its current value, as a YAML case file that reruns the case.
  std::string to_yaml() const {
    YAML::Emitter out;
    out << YAML::Comment(program_ + " case: every option with the value the run used; rerun with " + program_ +
                         " --case-file case.yaml")
        << YAML::Newline;
    out << YAML::BeginMap;
    for (const auto& e : entries_) {
      out << YAML::Key << key_of(e.option) << YAML::Value;
      if (e.is_string) out << YAML::DoubleQuoted;
      out << e.value() << YAML::Comment(e.option->get_description());
    }
    out << YAML::EndMap << YAML::Newline;
    return out.c_str();
  }

  // Writes to_yaml() as `directory/case.yaml`. Throws std::runtime_error if it cannot.
  void write_case(const std::string& directory) const {
    const std::string path = directory + "/case.yaml";
    std::ofstream file(path);
    file << to_yaml();
    if (!file) throw std::runtime_error("cannot write " + path);
  }

  // Handles --print-case for main(): prints the case and returns true (the program then stops).
  bool print_case_if_requested() const {
    if (print_case_) std::fputs(to_yaml().c_str(), stdout);
    return print_case_;
  }

 private:
  struct Entry {
    CLI::Option* option;
    std::function<std::string()> value;
    bool is_string;
  };

  static std::string key_of(const CLI::Option* opt) { return opt->get_single_name(); }

  void apply_case_file(const std::string& path) {
    const std::string where = "case file " + path;
    std::ifstream in(path);
    if (!in) throw UsageError(where + ": cannot be read");
    YAML::Node root;
    try {
      root = YAML::Load(in);
    } catch (const YAML::Exception& e) {
      throw UsageError(where + ": not valid YAML (line " + std::to_string(e.mark.line + 1) + ": " + e.msg + ")");
    }
    if (root.IsNull()) return;  // an empty file sets nothing
    if (!root.IsMap()) throw UsageError(where + ": expected a map of option names to values");
    std::set<std::string> seen;
    for (const auto& item : root) {
      const std::string key = item.first.IsScalar() ? item.first.Scalar() : std::string("?");
      if (!seen.insert(key).second) throw UsageError(where + ": key '" + key + "' is given twice");
      const Entry* entry = find(key);
      if (!entry) throw UsageError(where + ": unknown key '" + key + "' (" + program_ + " --help lists the options)");
      if (!item.second.IsScalar())
        throw UsageError(where + ": key '" + key + "' needs a single value, not " +
                         (item.second.IsNull() ? "nothing" : item.second.IsMap() ? "a map" : "a list"));
      if (entry->option->count() > 0) continue;  // the command line overrides the file
      try {
        entry->option->add_result(item.second.Scalar());
        entry->option->run_callback();
      } catch (const CLI::Error& e) {
        throw UsageError(where + ": key '" + key + "': " + e.what());
      }
    }
  }

  const Entry* find(const std::string& key) const {
    for (const auto& e : entries_)
      if (key_of(e.option) == key) return &e;
    return nullptr;
  }

  std::string program_;
  CLI::App app_;
  std::string case_file_;
  bool print_case_ = false;
  std::vector<Entry> entries_;
};

}  // namespace mpsfsi_examples
