#include "tests/support/test_support.h"

#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <cstdio>
#include <cstdlib>

namespace wardmap::test {

namespace fs = std::filesystem;

static fs::path env_or(const char* var, const fs::path& fallback) {
  if (const char* v = std::getenv(var); v && *v) return fs::path(v);
  return fallback;
}

fs::path shared_data_dir() {
  fs::path p = env_or("WARDMAP_DATA", fs::path(WARDMAP_SHARED_DIR) / "data");
  return fs::is_directory(p) ? p : fs::path();
}

fs::path shared_models_dir() {
  fs::path p = env_or("WARDMAP_MODELS", fs::path(WARDMAP_SHARED_DIR) / "models");
  return fs::is_directory(p) ? p : fs::path();
}

fs::path source_dir() { return env_or("WARDMAP_SOURCE_DIR", fs::path(WARDMAP_PROJECT_DIR)); }

fs::path binary_dir() { return fs::path(WARDMAP_BINARY_DIR); }

// This test process's scratch folders live under one root.
static fs::path process_scratch_root() {
  return fs::temp_directory_path() / ("wardmap-test-" + std::to_string(::getpid()));
}

namespace {
// Removes the process's scratch folders after its last test when every test passed (ctest runs each
// test in its own process, so they would pile up in the temporary folder); a failed run keeps them
// to be looked at, and says where.
class ScratchCleanup : public ::testing::Environment {
 public:
  void TearDown() override {
    const fs::path root = process_scratch_root();
    std::error_code ec;
    if (!fs::exists(root, ec)) return;
    if (!::testing::UnitTest::GetInstance()->Passed()) {
      std::fprintf(stderr, "scratch files of the failed test kept in %s\n", root.c_str());
      return;
    }
    fs::remove_all(root, ec);
    if (ec) std::fprintf(stderr, "could not remove scratch folder %s: %s\n", root.c_str(), ec.message().c_str());
  }
};
[[maybe_unused]] ::testing::Environment* const scratch_cleanup =
    ::testing::AddGlobalTestEnvironment(new ScratchCleanup);
}  // namespace

fs::path scratch_dir() {
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  std::string name = info ? std::string(info->test_suite_name()) + "." + info->name() : "scratch";
  for (char& c : name)
    if (c == '/') c = '_';
  fs::path p = process_scratch_root() / name;
  fs::remove_all(p);
  fs::create_directories(p);
  return p;
}

int run_command(const std::string& cmd, std::string* output) {
  std::string full = cmd + " 2>&1";
  FILE* pipe = ::popen(full.c_str(), "r");
  if (!pipe) return -1;
  std::array<char, 4096> buf;
  std::string out;
  size_t n;
  while ((n = std::fread(buf.data(), 1, buf.size(), pipe)) > 0) out.append(buf.data(), n);
  int status = ::pclose(pipe);
  if (output) *output = out;
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

}  // namespace wardmap::test
