// Runs the built wardmap executable.
#pragma once

#include <string>

#include "tests/support/test_support.h"

namespace wardmap::test {

struct CliResult {
  int code;
  std::string output;
};

inline CliResult wardmap_cli(const std::string& args) {
  CliResult r;
  r.code = run_command((binary_dir() / "apps" / "wardmap").string() + " " + args, &r.output);
  return r;
}

inline std::string shq(const std::filesystem::path& p) { return "'" + p.string() + "'"; }

}  // namespace wardmap::test
