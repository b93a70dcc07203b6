// A scenario: the hospital layout (floor, ceiling, wall segments, object rows), the camera path
// (waypoints) and the challenge segments, as read from data/scenarios/<name>.yaml.
// World frame: z up, metres; the floor is z = 0. Yaw is measured in the x-y plane from +x towards +y.
#pragma once

#include <Eigen/Core>
#include <filesystem>
#include <string>
#include <vector>

namespace wardmap::sim {

enum class ObjectClass { kDoor, kChair, kBed, kCabinet, kWheelchair, kIvPole };
// "door", "chair", "bed", "cabinet", "wheelchair", "iv_pole", in enum order.
const std::vector<std::string>& object_class_names();
const std::string& to_string(ObjectClass c);
// Number of appearance variants each class has.
int variant_count(ObjectClass c);

enum class Platform { kRobot, kDrone };
enum class ChallengeKind { kBlur, kTextureless, kDark, kFastTurn };
// "blur", "textureless", "dark", "fast-turn" (the words of challenges.txt).
const std::string& to_string(ChallengeKind k);

struct WallSpec {
  Eigen::Vector2d from = Eigen::Vector2d::Zero(), to = Eigen::Vector2d::Zero();
  std::string texture = "paint";  // paint | speckle | plain | tiles | wood
  int posters = 0;                // posters and notices per face
  bool handrail = false;
};

// One entry of `objects:`; count > 1 makes a row of identical instances along the object's own x.
struct ObjectSpec {
  ObjectClass cls = ObjectClass::kChair;
  Eigen::Vector2d at = Eigen::Vector2d::Zero();  // floor point under the first instance's centre
  double elevation = 0.0;                        // bottom of the box above the floor
  double yaw_deg = 0.0;                          // the object's front (+y) is rotated by yaw from +y
  int count = 1;
  double spacing = 1.0;  // centre-to-centre along the row
  int variant = -1;      // -1: chosen from the seed (one choice for the whole row)
  bool jitter = true;
};

struct WaypointSpec {
  Eigen::Vector3d position = Eigen::Vector3d::Zero();
  bool has_look_at = false;
  Eigen::Vector3d look_at = Eigen::Vector3d::Zero();
  double yaw_deg = 0.0, pitch_deg = 0.0, roll_deg = 0.0;
  double duration = -1.0;  // seconds from the previous waypoint in the slow variant; < 0: automatic
  std::string name;
};

// A challenge spans the path between two waypoints (indices into path.waypoints).
struct ChallengeSpec {
  ChallengeKind kind = ChallengeKind::kBlur;
  int from = 0, to = 0;
  double strength = 1.0;  // blur: shake amplitude scale; dark: remaining light fraction (gain)
};

struct Scenario {
  std::string name, description;
  std::string file;  // where it was read from (for messages)
  Platform platform = Platform::kRobot;
  double position_jitter = 0.05;  // metres, uniform +-
  double yaw_jitter_deg = 2.0;
  Eigen::Vector2d floor_min = Eigen::Vector2d::Zero(), floor_max = Eigen::Vector2d::Zero();
  std::string floor_texture = "tiles";  // tiles | lino | plain
  double ceiling_height = 2.8;
  std::vector<WallSpec> walls;
  std::vector<ObjectSpec> objects;
  double speed = 0.8;           // m/s, slow variant
  double turn_rate_deg = 40.0;  // deg/s, slow variant
  double quick_factor = 0.5;    // the quick variant's durations = slow durations * quick_factor
  std::vector<WaypointSpec> waypoints;
  std::vector<ChallengeSpec> challenges;
};

// Parse and validate; throws wardmap::InputError naming the file, line and key
// (e.g. "key 'objects[3].class': unknown class 'sofa' (allowed: door, chair, ...)").
Scenario parse_scenario(const std::string& yaml_text, const std::string& file_label);
Scenario load_scenario(const std::filesystem::path& file);

// Built-in scenarios: the folder holding <name>.yaml files. Looked up in $WARDMAP_SCENARIOS, beside
// the executable (../share/wardmap/scenarios, ../data/scenarios, ../../data/scenarios) and in the
// source tree the library was built from. Empty when none exists.
std::filesystem::path builtin_scenario_dir();
// Names of the built-ins (sorted file stems of *.yaml in builtin_scenario_dir()).
std::vector<std::string> builtin_scenarios();
// A path to an existing file, or a built-in name; otherwise InputError listing the built-ins.
std::filesystem::path resolve_scenario(const std::string& name_or_file);

}  // namespace wardmap::sim
