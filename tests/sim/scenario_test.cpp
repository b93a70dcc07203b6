// Scenario files: the built-ins load, and every error names the key (and line) that is wrong.
#include "sim/scenario.h"

#include <gtest/gtest.h>

#include "slam/core/errors.h"
#include "tests/sim/sim_test_util.h"

namespace wardmap::sim {
namespace {

const char* kMinimal = R"(
name: tiny
structure:
  floor: {min: [0, 0], max: [4, 3]}
  walls:
    - {from: [0, 0], to: [4, 0]}
objects:
  - {class: chair, at: [1, 1]}
  - {class: bed, at: [2, 1]}
  - {class: door, at: [1, 0]}
  - {class: CLASS, at: [3, 1]}
path:
  waypoints:
    - {position: [0.5, 1.5], yaw_deg: 0}
    - {position: [3.0, 1.5], yaw_deg: 0}
)";

std::string with(const std::string& from, const std::string& to) {
  std::string s = kMinimal;
  s.replace(s.find(from), from.size(), to);
  return s;
}

std::string error_of(const std::string& yaml) {
  try {
    parse_scenario(yaml, "test.yaml");
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(Scenario, BuiltinsLoad) {
  for (const std::string name : {"aisle_straight", "aisle_left_turn", "aisle_right_turn", "ward", "corridor_loss"}) {
    SCOPED_TRACE(name);
    const Scenario s = testing::builtin(name);
    EXPECT_EQ(s.name, name);
    EXPECT_GE(s.objects.size(), 5u);
    EXPECT_GE(s.waypoints.size(), 2u);
  }
  EXPECT_FALSE(testing::builtin("corridor_loss").challenges.empty());
}

TEST(Scenario, MinimalParses) {
  const Scenario s = parse_scenario(with("CLASS", "cabinet"), "test.yaml");
  ASSERT_EQ(s.objects.size(), 4u);
  EXPECT_EQ(s.objects[3].cls, ObjectClass::kCabinet);
  EXPECT_DOUBLE_EQ(s.waypoints[0].position.z(), 1.2);  // robot default height
}

TEST(Scenario, UnknownClassNamesKeyAndAllowedValues) {
  const std::string e = error_of(with("CLASS", "sofa"));
  EXPECT_NE(e.find("test.yaml:11:"), std::string::npos) << e;
  EXPECT_NE(e.find("key 'objects[3].class': unknown class 'sofa' (allowed: door, chair, bed, cabinet, wheelchair, "
                   "iv_pole)"),
            std::string::npos)
      << e;
}

TEST(Scenario, ErrorsNameTheKey) {
  EXPECT_NE(error_of(with("{class: chair, at: [1, 1]}", "{class: chair, at: [1, 1], colour: red}"))
                .find("'objects[0].colour': unknown key"),
            std::string::npos);
  EXPECT_NE(error_of(with("at: [2, 1]", "at: [2, x]")).find("'objects[1].at[1]': must be a number"), std::string::npos);
  EXPECT_NE(error_of(with("{class: chair, at: [1, 1]}", "{class: chair, at: [1, 1], count: 0}"))
                .find("'objects[0].count': value 0 out of range [1, 50]"),
            std::string::npos);
  EXPECT_NE(error_of(with("max: [4, 3]", "max: [-1, 3]")).find("'structure.floor.max'"), std::string::npos);
  EXPECT_NE(error_of(with("  walls:\n    - {from: [0, 0], to: [4, 0]}\n", "")).find("'structure.walls': missing"),
            std::string::npos);
  EXPECT_NE(error_of(with("CLASS", "cabinet") + "challenges:\n  - {kind: dark, from: 0, to: 5}\n")
                .find("'challenges[0].to': value 5 out of range [0, 1]"),
            std::string::npos);
  EXPECT_NE(
      error_of(with("CLASS", "cabinet") + "challenges:\n  - {kind: fog, from: 0, to: 1}\n")
          .find("'challenges[0].kind': unknown challenge kind 'fog' (allowed: blur, textureless, dark, fast-turn)"),
      std::string::npos);
  EXPECT_NE(error_of(with("CLASS", "door, variant: 7")).find("'objects[3].variant': value 7 out of range [-1, 2]"),
            std::string::npos);
  EXPECT_NE(error_of("name: [unclosed").find("YAML syntax error"), std::string::npos);
  // Before: an object or a waypoint off the floor rendered a sequence without it in view, or from
  // outside the walls.
  EXPECT_EQ(error_of(with("at: [2, 1]", "at: [20, 1]")),
            "test.yaml:9: key 'objects[1].at': outside the floor (x 0 to 4, y 0 to 3)");
  std::string high = with("CLASS", "cabinet");
  high.replace(high.find("[3.0, 1.5]"), 10, "[3.0, 1.5, 3.0]");
  EXPECT_EQ(error_of(high),
            "test.yaml:15: key 'path.waypoints[1].position': outside the room (x 0 to 4, y 0 to 3, z 0 to 2.8)");
}

TEST(Scenario, ResolveNamesAndFiles) {
  EXPECT_EQ(resolve_scenario(testing::scenario_file("ward").string()), testing::scenario_file("ward"));
  const auto names = builtin_scenarios();
  EXPECT_NE(std::find(names.begin(), names.end(), "corridor_loss"), names.end());
  try {
    resolve_scenario("no_such_scenario");
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("built-ins: aisle_left_turn, aisle_right_turn, aisle_straight"),
              std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace wardmap::sim
