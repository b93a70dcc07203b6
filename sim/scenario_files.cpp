// Where the built-in scenarios live and how a --scenario argument resolves to a file.
#include <unistd.h>

#include <algorithm>
#include <cstdlib>

#include "sim/scenario.h"
#include "slam/core/errors.h"

namespace wardmap::sim {

namespace fs = std::filesystem;

namespace {
fs::path executable_dir() {
  std::error_code ec;
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  return ec ? fs::path() : exe.parent_path();
}
bool has_yaml(const fs::path& dir) {
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) return false;
  for (const auto& e : fs::directory_iterator(dir, ec))
    if (e.path().extension() == ".yaml") return true;
  return false;
}
}  // namespace

fs::path builtin_scenario_dir() {
  std::vector<fs::path> candidates;
  // NOLINTNEXTLINE(concurrency-mt-unsafe): wardmap never calls setenv
  if (const char* env = std::getenv("WARDMAP_SCENARIOS")) candidates.emplace_back(env);
  const fs::path exe = executable_dir();
  if (!exe.empty()) {
    candidates.push_back(exe / ".." / "share" / "wardmap" / "scenarios");
    candidates.push_back(exe / ".." / "data" / "scenarios");
    candidates.push_back(exe / ".." / ".." / "data" / "scenarios");
  }
#ifdef WARDMAP_SCENARIO_DIR
  candidates.emplace_back(WARDMAP_SCENARIO_DIR);
#endif
  for (const auto& c : candidates)
    if (has_yaml(c)) return c.lexically_normal();
  return {};
}

std::vector<std::string> builtin_scenarios() {
  std::vector<std::string> names;
  const fs::path dir = builtin_scenario_dir();
  if (dir.empty()) return names;
  for (const auto& e : fs::directory_iterator(dir))
    if (e.path().extension() == ".yaml") names.push_back(e.path().stem().string());
  std::sort(names.begin(), names.end());
  return names;
}

fs::path resolve_scenario(const std::string& name_or_file) {
  std::error_code ec;
  if (fs::is_regular_file(name_or_file, ec)) return name_or_file;
  const auto names = builtin_scenarios();
  if (std::find(names.begin(), names.end(), name_or_file) != names.end())
    return builtin_scenario_dir() / (name_or_file + ".yaml");
  std::string list;
  for (const auto& n : names) list += (list.empty() ? "" : ", ") + n;
  if (list.empty()) list = "none found; set WARDMAP_SCENARIOS to the data/scenarios folder";
  throw InputError(name_or_file, "neither a scenario file nor a built-in scenario (built-ins: " + list + ")");
}

}  // namespace wardmap::sim
