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

// Runs wardmap with `args` in the background, its stderr to `err`, and sends it `signal` ("INT",
// "TERM") `delay` seconds after its stderr shows `started`: its handlers are in place by then, where
// a fixed time would meet the default action on a slow start-up (sanitizers, a loaded machine).
// The result's output is the stderr.
inline CliResult wardmap_cli_signalled(const std::string& args, const std::filesystem::path& err,
                                       const std::string& started, const std::string& signal,
                                       const std::string& delay) {
  CliResult r;
  r.code = run_command((binary_dir() / "apps" / "wardmap").string() + " " + args + " 2>" + shq(err) +
                           " & pid=$!; for i in $(seq 3000); do grep -q '" + started + "' " + shq(err) +
                           " && break; sleep 0.02; done; sleep " + delay + "; kill -" + signal +
                           " $pid; wait $pid; code=$?; cat " + shq(err) + "; exit $code",
                       &r.output);
  return r;
}

}  // namespace wardmap::test
