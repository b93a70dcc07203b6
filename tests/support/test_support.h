// Helpers shared by the tests: where the shared data and models are, scratch folders.
#pragma once

#include <filesystem>
#include <string>

namespace wardmap::test {

// ../shared/data (or $WARDMAP_DATA); empty when absent.
std::filesystem::path shared_data_dir();
// ../shared/models (or $WARDMAP_MODELS); empty when absent.
std::filesystem::path shared_models_dir();
// The project's source tree (for data/settings, data/scenarios).
std::filesystem::path source_dir();
// The build tree (for the wardmap executable).
std::filesystem::path binary_dir();
// A fresh, empty scratch folder unique to the running test; removed after the process's last
// test when all its tests passed, kept (and named on stderr) when one failed.
std::filesystem::path scratch_dir();

// Run a shell command, capture stdout+stderr; returns the exit code.
int run_command(const std::string& cmd, std::string* output = nullptr);

}  // namespace wardmap::test

// Skip the test (with the reason) when a shared sequence is missing.
#define WARDMAP_REQUIRE_DATA(sub)                                                                  \
  do {                                                                                             \
    if (::wardmap::test::shared_data_dir().empty() ||                                              \
        !std::filesystem::exists(::wardmap::test::shared_data_dir() / (sub)))                      \
      GTEST_SKIP() << "shared data '" << (sub) << "' not found (set WARDMAP_DATA or put ../shared beside the checkout)"; \
  } while (0)
