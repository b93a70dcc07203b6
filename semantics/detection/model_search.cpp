#include "semantics/detection/model_search.h"

#include <cstdlib>

#include "slam/core/errors.h"

namespace wardmap::semantics {

namespace fs = std::filesystem;

namespace {
// Relative file of the OSNet x0.25 re-id model inside a models folder (MODELS.md).
constexpr const char* kOsnetFile = "osnet-x0_25/osnet_x0_25_msmt17.onnx";
}  // namespace

std::vector<fs::path> model_search_path(const fs::path& models_dir) {
  std::vector<fs::path> dirs;
  if (!models_dir.empty()) dirs.push_back(models_dir);
  // NOLINTNEXTLINE(concurrency-mt-unsafe): wardmap never calls setenv
  if (const char* env = std::getenv("WARDMAP_MODELS"); env && *env) dirs.emplace_back(env);
  dirs.emplace_back(WARDMAP_DEFAULT_MODELS_DIR);
  return dirs;
}

namespace {

// Whether `file` is a regular file; one that exists as something else (a folder) is an error, not a
// reason to take another folder's copy without a word.
bool is_model_file(const fs::path& file) {
  if (fs::is_regular_file(file)) return true;
  if (fs::exists(file)) throw InputError(file.string(), "is not a regular file (a folder?), not a model file");
  return false;
}

}  // namespace

fs::path find_model_file(const fs::path& relative, const fs::path& models_dir) {
  if (relative.is_absolute()) {
    if (is_model_file(relative)) return relative;
    throw InputError(relative.string(), "model file not found");
  }
  // A folder the user named (flag, settings or environment: all but the last, compiled-in place)
  // that does not exist is a mistake, not a reason to fall back silently on the next place.
  const std::vector<fs::path> dirs = model_search_path(models_dir);
  for (size_t i = 0; i + 1 < dirs.size(); ++i)
    if (!fs::is_directory(dirs[i]))
      throw InputError(dirs[i].string(), std::string("models folder not found (given as ") +
                                             (dirs[i] == models_dir ? "--models or detection.models_dir" : "$WARDMAP_MODELS") + ")");
  std::string looked;
  for (const fs::path& dir : dirs) {
    const fs::path candidate = dir / relative;
    if (is_model_file(candidate)) return candidate;
    looked += (looked.empty() ? "" : ", ") + candidate.string();
  }
  throw InputError(
      relative.string(),
      "model file not found; looked in: " + looked +
          " (set detection.models_dir or $WARDMAP_MODELS; models/README.md says where to get the weights)");
}

fs::path model_descriptions_dir() { return fs::path(WARDMAP_MODEL_DESCRIPTIONS_DIR); }

fs::path find_embedder_file(const fs::path& models_dir) { return find_model_file(kOsnetFile, models_dir); }

}  // namespace wardmap::semantics
