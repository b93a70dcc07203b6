// Reading objects.json and measurements.jsonl back: what the writers wrote, and bad files refused with
// an InputError naming the file (and the line of a measurement).
#include "semantics/object_map_io.h"

#include <gtest/gtest.h>

#include <fstream>

#include "slam/core/errors.h"
#include "tests/support/test_support.h"

namespace wardmap::semantics {
namespace {

namespace fs = std::filesystem;

std::string error_of_reading(const fs::path& file, const std::string& text, bool objects) {
  std::ofstream(file) << text;
  try {
    if (objects)
      read_objects_json(file);
    else
      read_measurements_jsonl(file);
  } catch (const InputError& e) {
    return e.what();
  }
  return "(no error)";
}

// A number too large for a double is nlohmann's out_of_range, not a parse_error: it was let through.
TEST(ObjectMapIo, NumbersTooLargeAreInputErrors) {
  const fs::path dir = test::scratch_dir();
  const fs::path objects = dir / "objects.json", measurements = dir / "measurements.jsonl";
  std::string e = error_of_reading(objects, R"({"objects": [{"id": 1, "position": [4e400, 0, 0]}]})", true);
  EXPECT_EQ(e.rfind(objects.string() + ": JSON syntax error: ", 0), 0u) << e;
  EXPECT_NE(e.find("number overflow"), std::string::npos) << e;
  e = error_of_reading(measurements, "\n" + std::string(R"({"keyframe": 0, "timestamp": 1e999})"), false);
  EXPECT_EQ(e.rfind(measurements.string() + ":2: malformed measurement: ", 0), 0u) << e;
  EXPECT_NE(e.find("number overflow"), std::string::npos) << e;
}

}  // namespace
}  // namespace wardmap::semantics
