#include "tests/support/test_support.h"

#include <gtest/gtest.h>

#include <array>
#include <cstdio>
#include <cstdlib>
#include <sys/wait.h>

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

fs::path scratch_dir() {
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  std::string name = info ? std::string(info->test_suite_name()) + "." + info->name() : "scratch";
  for (char& c : name)
    if (c == '/') c = '_';
  fs::path p = fs::temp_directory_path() / ("wardmap-test-" + std::to_string(::getpid())) / name;
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
