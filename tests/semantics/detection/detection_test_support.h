// Helpers for the detection tests: skipping when the shared models or photos are absent, printing.
#pragma once

#include <gtest/gtest.h>

#include <filesystem>
#include <iomanip>
#include <sstream>
#include <string>
#include <vector>

#include "semantics/detection/detection.h"
#include "tests/support/test_support.h"

// Skip the test (with the reason) when a file under ../shared/models is missing.
#define WARDMAP_REQUIRE_MODEL(relative)                                                               \
  do {                                                                                                \
    if (::wardmap::test::shared_models_dir().empty() ||                                               \
        !std::filesystem::exists(::wardmap::test::shared_models_dir() / (relative)))                  \
      GTEST_SKIP() << "shared model '" << (relative)                                                  \
                   << "' not found (set WARDMAP_MODELS or put ../shared/models beside the checkout)"; \
  } while (0)

namespace wardmap::semantics::test {

inline std::string describe(const std::vector<Detection>& dets) {
  std::ostringstream s;
  s << std::fixed << std::setprecision(2);
  for (const Detection& d : dets)
    s << "  " << std::setw(14) << std::left << d.label << " (" << d.source_label << ") score " << d.score << "  box ["
      << std::setprecision(0) << d.box[0] << ", " << d.box[1] << ", " << d.box[2] << ", " << d.box[3] << "]"
      << std::setprecision(2) << "\n";
  return s.str();
}

}  // namespace wardmap::semantics::test
