// Shared helpers for the sim tests.
#pragma once

#include <string>

#include "sim/scenario.h"
#include "tests/support/test_support.h"

namespace wardmap::sim::testing {

inline std::filesystem::path scenario_file(const std::string& name) {
  return wardmap::test::source_dir() / "data" / "scenarios" / (name + ".yaml");
}
inline Scenario builtin(const std::string& name) { return load_scenario(scenario_file(name)); }

}  // namespace wardmap::sim::testing
