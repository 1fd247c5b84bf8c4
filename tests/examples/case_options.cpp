// SPDX-License-Identifier: BSD-3-Clause
// The examples' command line and case files (examples/common/case_options.hpp): precedence of
// command line over case file, the resolved case read back, and a clear UsageError naming the
// option or key for every kind of bad input.
#include <doctest/doctest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "common/case_options.hpp"

using mpsfsi_examples::CaseOptions;
using mpsfsi_examples::UsageError;

namespace {

struct Case {
  double l0 = 0.002;
  int dim = 2;
  std::string scheme = "explicit";
  bool quiet = false;
};

struct Parser {
  Case c;
  CaseOptions options{"demo", "a test case"};
  Parser() {
    options.add("--l0", c.l0, "initial particle spacing", "m")->check(mpsfsi_examples::positive());
    options.add("--dim", c.dim, "dimension")->check(mpsfsi_examples::one_of({"2", "3"}));
    options.add("--scheme", c.scheme, "coupling scheme")->check(mpsfsi_examples::one_of({"explicit", "iterated"}));
    options.flag("--quiet", c.quiet, "no output");
  }
  bool parse(std::vector<std::string> args) {
    args.insert(args.begin(), "demo");
    std::vector<const char*> argv;
    for (const auto& a : args) argv.push_back(a.c_str());
    return options.parse(static_cast<int>(argv.size()), argv.data());
  }
};

std::string write_file(const std::string& name, const std::string& text) {
  const auto path = (std::filesystem::temp_directory_path() / ("mpsfsi_case_options_" + name)).string();
  std::ofstream(path) << text;
  return path;
}

std::string error_of(std::vector<std::string> args) {
  Parser p;
  try {
    p.parse(std::move(args));
  } catch (const UsageError& e) {
    return e.what();
  }
  return "no error";
}

}  // namespace

TEST_SUITE("examples") {

TEST_CASE("case options: defaults, command line, and case file with the command line on top") {
  Parser defaults;
  CHECK(defaults.parse({}));
  CHECK(defaults.c.l0 == 0.002);

  Parser cli;
  CHECK(cli.parse({"--l0", "0.001", "--dim", "3", "--quiet"}));
  CHECK(cli.c.l0 == 0.001);
  CHECK(cli.c.dim == 3);
  CHECK(cli.c.quiet);

  const auto file = write_file("precedence.yaml", "l0: 0.004\ndim: 3\nscheme: iterated\nquiet: true\n");
  Parser both;
  CHECK(both.parse({"--case-file", file, "--l0", "0.003"}));
  CHECK(both.c.l0 == 0.003);  // the command line wins
  CHECK(both.c.dim == 3);
  CHECK(both.c.scheme == "iterated");
  CHECK(both.c.quiet);
}

TEST_CASE("case options: the written case reads back to the same values") {
  Parser first;
  CHECK(first.parse({"--l0", "0.0013", "--scheme", "iterated"}));
  first.c.dim = 3;  // a default the program resolved after parsing is written as resolved
  const std::string yaml = first.options.to_yaml();
  CHECK(yaml.find("l0: 0.0013") != std::string::npos);
  CHECK(yaml.find("[m]") != std::string::npos);  // help text and unit as a comment
  const auto file = write_file("roundtrip.yaml", yaml);
  Parser second;
  CHECK(second.parse({"--case-file", file}));
  CHECK(second.c.l0 == first.c.l0);
  CHECK(second.c.dim == 3);
  CHECK(second.c.scheme == "iterated");
  CHECK(second.c.quiet == false);
  CHECK(second.options.to_yaml() == yaml);
}

TEST_CASE("case options: bad command lines name the option") {
  CHECK(error_of({"--l0", "abc"}) == "--l0: must be a number, not abc");
  CHECK(error_of({"--dim", "2.5"}) == "--dim: must be a whole number, not 2.5");
  CHECK(error_of({"--l0", "-1"}) == "--l0: must be a positive number, not -1");
  CHECK(error_of({"--l0", "nan"}).find("must be finite") != std::string::npos);
  CHECK(error_of({"--l0", "inf"}).find("must be finite") != std::string::npos);
  CHECK(error_of({"--dim", "4"}) == "--dim: must be one of 2|3, not 4");
  CHECK(error_of({"--scheme", "implicit"}).find("explicit|iterated") != std::string::npos);
  CHECK(error_of({"--bogus", "1"}) == "unknown option or stray argument: --bogus 1");
  CHECK(error_of({"--l0"}).find("--l0") != std::string::npos);
  CHECK(error_of({"stray"}).find("stray") != std::string::npos);
}

TEST_CASE("case options: bad case files name the file and the key") {
  const auto unknown = write_file("unknown.yaml", "l0: 0.002\nspeeed: 3\n");
  CHECK(error_of({"--case-file", unknown}).find("unknown key 'speeed'") != std::string::npos);
  const auto type = write_file("type.yaml", "l0: fast\n");
  const std::string type_error = error_of({"--case-file", type});
  CHECK(type_error.find(type) != std::string::npos);
  CHECK(type_error.find("key 'l0'") != std::string::npos);
  CHECK(error_of({"--case-file", write_file("range.yaml", "dim: 4\n")}).find("key 'dim': --dim: must be one of 2|3") !=
        std::string::npos);
  CHECK(error_of({"--case-file", write_file("list.yaml", "l0: [1, 2]\n")}).find("needs a single value, not a list") !=
        std::string::npos);
  CHECK(error_of({"--case-file", write_file("flag.yaml", "quiet: maybe\n")}).find("key 'quiet'") != std::string::npos);
  CHECK(error_of({"--case-file", write_file("twice.yaml", "l0: 1\nl0: 2\n")}).find("given twice") != std::string::npos);
  CHECK(error_of({"--case-file", write_file("broken.yaml", "l0: [1, 2\n")}).find("not valid YAML") != std::string::npos);
  CHECK(error_of({"--case-file", write_file("scalar.yaml", "just text\n")}).find("expected a map") != std::string::npos);
  CHECK(error_of({"--case-file", "/nonexistent/case.yaml"}).find("cannot be read") != std::string::npos);
  Parser empty;  // an empty file sets nothing
  CHECK(empty.parse({"--case-file", write_file("empty.yaml", "")}));
  CHECK(empty.c.l0 == 0.002);
}

TEST_CASE("case options: --help lists every option with its default and unit") {
  Parser p;
  const std::string help = p.options.app().help();
  CHECK(help.find("--l0") != std::string::npos);
  CHECK(help.find("=0.002") != std::string::npos);
  CHECK(help.find("[m]") != std::string::npos);
  CHECK(help.find("--case-file") != std::string::npos);
  CHECK(help.find("explicit|iterated") != std::string::npos);
}

}  // TEST_SUITE
