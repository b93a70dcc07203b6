#pragma once

#include <cstdlib>
#include <filesystem>

namespace wardmap::bench {

// ../shared/data, or $WARDMAP_DATA.
inline std::filesystem::path data_dir() {
  // NOLINTNEXTLINE(concurrency-mt-unsafe): wardmap never calls setenv
  if (const char* v = std::getenv("WARDMAP_DATA"); v && *v) return v;
  return std::filesystem::path(WARDMAP_SHARED_DIR) / "data";
}

}  // namespace wardmap::bench
