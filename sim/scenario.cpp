#include "sim/scenario.h"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <set>
#include <sstream>

#include "slam/core/errors.h"

namespace wardmap::sim {

const std::vector<std::string>& object_class_names() {
  static const std::vector<std::string> names = {"door", "chair", "bed", "cabinet", "wheelchair", "iv_pole"};
  return names;
}
const std::string& to_string(ObjectClass c) { return object_class_names()[static_cast<size_t>(c)]; }

int variant_count(ObjectClass c) {
  switch (c) {
    case ObjectClass::kDoor:
    case ObjectClass::kChair:
    case ObjectClass::kCabinet:
      return 3;
    case ObjectClass::kBed:
    case ObjectClass::kWheelchair:
    case ObjectClass::kIvPole:
      return 2;
  }
  return 1;
}

const std::string& to_string(ChallengeKind k) {
  static const std::vector<std::string> names = {"blur", "textureless", "dark", "fast-turn"};
  return names[static_cast<size_t>(k)];
}

namespace {

std::string join(const std::vector<std::string>& v) {
  std::string s;
  for (size_t i = 0; i < v.size(); ++i) s += (i ? ", " : "") + v[i];
  return s;
}

// Reads one YAML mapping, remembering the key path for messages and rejecting unknown keys.
class Reader {
 public:
  Reader(const std::string& file, const YAML::Node& node, std::string path)
      : file_(file), node_(node), path_(std::move(path)) {
    if (!node_.IsMap()) fail(node_, path_.empty() ? "(top level)" : path_, "must be a mapping");
  }

  [[noreturn]] void fail(const YAML::Node& at, const std::string& key, const std::string& problem) const {
    const long line = at.IsDefined() ? static_cast<long>(at.Mark().line) + 1 : 0;
    throw InputError(file_, "key '" + key + "': " + problem, line > 0 ? line : 0);
  }
  std::string key(const std::string& k) const { return path_.empty() ? k : path_ + "." + k; }
  bool has(const std::string& k) const { return node_[k].IsDefined() && !node_[k].IsNull(); }
  YAML::Node get(const std::string& k) const { return node_[k]; }

  void allow_only(const std::vector<std::string>& allowed) const {
    for (const auto& kv : node_) {
      const std::string k = kv.first.as<std::string>();
      if (std::find(allowed.begin(), allowed.end(), k) == allowed.end())
        fail(kv.first, key(k), "unknown key (allowed: " + join(allowed) + ")");
    }
  }
  YAML::Node required(const std::string& k) const {
    if (!has(k)) fail(node_, key(k), "missing");
    return node_[k];
  }

  double number(const std::string& k, double def, double lo, double hi) const {
    if (!has(k)) return def;
    return to_number(node_[k], key(k), lo, hi);
  }
  double required_number(const std::string& k, double lo, double hi) const {
    return to_number(required(k), key(k), lo, hi);
  }
  int integer(const std::string& k, int def, int lo, int hi) const {
    if (!has(k)) return def;
    const double v = to_number(node_[k], key(k), lo, hi);
    if (v != std::floor(v)) fail(node_[k], key(k), "must be a whole number");
    return static_cast<int>(v);
  }
  bool boolean(const std::string& k, bool def) const {
    if (!has(k)) return def;
    try {
      return node_[k].as<bool>();
    } catch (const YAML::Exception&) {
      fail(node_[k], key(k), "must be true or false");
    }
  }
  std::string text(const std::string& k, const std::string& def) const {
    if (!has(k)) return def;
    if (!node_[k].IsScalar()) fail(node_[k], key(k), "must be a string");
    return node_[k].as<std::string>();
  }
  std::string choice(const std::string& k, const std::string& def, const std::vector<std::string>& allowed,
                     const std::string& what) const {
    const std::string v = text(k, def);
    if (std::find(allowed.begin(), allowed.end(), v) == allowed.end())
      fail(node_[k], key(k), "unknown " + what + " '" + v + "' (allowed: " + join(allowed) + ")");
    return v;
  }
  Eigen::VectorXd vector(const std::string& k, int min_n, int max_n, double lo, double hi) const {
    const YAML::Node n = required(k);
    if (!n.IsSequence() || static_cast<int>(n.size()) < min_n || static_cast<int>(n.size()) > max_n) {
      const std::string want =
          min_n == max_n ? std::to_string(min_n) : std::to_string(min_n) + " or " + std::to_string(max_n);
      fail(n, key(k), "must be a list of " + want + " numbers");
    }
    Eigen::VectorXd v(n.size());
    for (size_t i = 0; i < n.size(); ++i)
      v[static_cast<long>(i)] = to_number(n[i], key(k) + "[" + std::to_string(i) + "]", lo, hi);
    return v;
  }

 private:
  double to_number(const YAML::Node& n, const std::string& key, double lo, double hi) const {
    double v = 0;
    try {
      if (!n.IsScalar()) throw YAML::Exception(YAML::Mark(), "");
      v = n.as<double>();
    } catch (const YAML::Exception&) {
      fail(n, key, "must be a number");
    }
    if (!(v >= lo && v <= hi)) {
      std::ostringstream s;
      s << "value " << v << " out of range [" << lo << ", " << hi << "]";
      fail(n, key, s.str());
    }
    return v;
  }

  std::string file_;
  YAML::Node node_;
  std::string path_;
};

const std::vector<std::string> kWallTextures = {"paint", "speckle", "plain", "tiles", "wood"};
const std::vector<std::string> kFloorTextures = {"tiles", "lino", "plain"};
const std::vector<std::string> kChallengeKinds = {"blur", "textureless", "dark", "fast-turn"};

// Objects stand, and the camera moves, over the floor's rectangle.
bool on_floor(const Scenario& s, const Eigen::Vector2d& xy) {
  return (xy.array() >= s.floor_min.array()).all() && (xy.array() <= s.floor_max.array()).all();
}

std::string floor_text(const Scenario& s) {
  std::ostringstream t;
  t << "x " << s.floor_min.x() << " to " << s.floor_max.x() << ", y " << s.floor_min.y() << " to " << s.floor_max.y();
  return t.str();
}

void parse_structure(const Reader& top, Scenario& s, const std::string& file) {
  const Reader st(file, top.required("structure"), "structure");
  st.allow_only({"floor", "ceiling_height", "walls"});
  const Reader fl(file, st.required("floor"), "structure.floor");
  fl.allow_only({"min", "max", "texture"});
  s.floor_min = fl.vector("min", 2, 2, -1000, 1000);
  s.floor_max = fl.vector("max", 2, 2, -1000, 1000);
  if (!(s.floor_max.array() > s.floor_min.array()).all())
    fl.fail(fl.get("max"), "structure.floor.max", "must be larger than structure.floor.min in x and y");
  s.floor_texture = fl.choice("texture", "tiles", kFloorTextures, "floor texture");
  s.ceiling_height = st.number("ceiling_height", 2.8, 2.2, 6.0);

  const YAML::Node walls = st.required("walls");
  if (!walls.IsSequence() || walls.size() == 0) st.fail(walls, "structure.walls", "must be a non-empty list");
  for (size_t i = 0; i < walls.size(); ++i) {
    const std::string path = "structure.walls[" + std::to_string(i) + "]";
    const Reader w(file, walls[i], path);
    w.allow_only({"from", "to", "texture", "posters", "handrail"});
    WallSpec spec;
    spec.from = w.vector("from", 2, 2, -1000, 1000);
    spec.to = w.vector("to", 2, 2, -1000, 1000);
    if ((spec.to - spec.from).norm() < 0.05) w.fail(walls[i], path + ".to", "wall shorter than 5 cm");
    spec.texture = w.choice("texture", "paint", kWallTextures, "wall texture");
    spec.posters = w.integer("posters", 0, 0, 200);
    spec.handrail = w.boolean("handrail", false);
    s.walls.push_back(spec);
  }
}

void parse_objects(const Reader& top, Scenario& s, const std::string& file) {
  if (!top.has("objects")) return;
  const YAML::Node objs = top.get("objects");
  if (!objs.IsSequence()) top.fail(objs, "objects", "must be a list");
  for (size_t i = 0; i < objs.size(); ++i) {
    const std::string path = "objects[" + std::to_string(i) + "]";
    const Reader o(file, objs[i], path);
    o.allow_only({"class", "at", "elevation", "yaw_deg", "count", "spacing", "variant", "jitter"});
    ObjectSpec spec;
    const std::string cls = o.choice("class", "", object_class_names(), "class");
    spec.cls = static_cast<ObjectClass>(std::find(object_class_names().begin(), object_class_names().end(), cls) -
                                        object_class_names().begin());
    spec.at = o.vector("at", 2, 2, -1000, 1000);
    if (!on_floor(s, spec.at)) o.fail(o.get("at"), path + ".at", "outside the floor (" + floor_text(s) + ")");
    spec.elevation = o.number("elevation", 0.0, 0.0, 3.0);
    spec.yaw_deg = o.number("yaw_deg", 0.0, -720, 720);
    spec.count = o.integer("count", 1, 1, 50);
    spec.spacing = o.number("spacing", 1.0, 0.2, 20.0);
    spec.variant = o.integer("variant", -1, -1, variant_count(spec.cls) - 1);
    spec.jitter = o.boolean("jitter", true);
    s.objects.push_back(spec);
  }
}

void parse_path(const Reader& top, Scenario& s, const std::string& file) {
  const Reader p(file, top.required("path"), "path");
  p.allow_only({"speed", "turn_rate_deg", "quick_factor", "waypoints"});
  s.speed = p.number("speed", 0.8, 0.05, 10.0);
  s.turn_rate_deg = p.number("turn_rate_deg", 40.0, 1.0, 2000.0);
  s.quick_factor = p.number("quick_factor", 0.5, 0.1, 1.0);
  const YAML::Node wps = p.required("waypoints");
  if (!wps.IsSequence() || wps.size() < 2) p.fail(wps, "path.waypoints", "must be a list of at least 2 waypoints");
  const double default_z = s.platform == Platform::kRobot ? 1.2 : 2.0;
  for (size_t i = 0; i < wps.size(); ++i) {
    const std::string path = "path.waypoints[" + std::to_string(i) + "]";
    const Reader w(file, wps[i], path);
    w.allow_only({"position", "look_at", "yaw_deg", "pitch_deg", "roll_deg", "duration", "name"});
    WaypointSpec spec;
    const Eigen::VectorXd pos = w.vector("position", 2, 3, -1000, 1000);
    spec.position = Eigen::Vector3d(pos[0], pos[1], pos.size() == 3 ? pos[2] : default_z);
    if (!on_floor(s, spec.position.head<2>()) || !(spec.position.z() > 0 && spec.position.z() < s.ceiling_height)) {
      std::ostringstream room;
      room << "outside the room (" << floor_text(s) << ", z 0 to " << s.ceiling_height << ")";
      w.fail(w.get("position"), path + ".position", room.str());
    }
    if (w.has("look_at")) {
      if (w.has("yaw_deg") || w.has("pitch_deg"))
        w.fail(w.get("look_at"), path + ".look_at", "give either look_at or yaw_deg/pitch_deg, not both");
      const Eigen::VectorXd la = w.vector("look_at", 2, 3, -1000, 1000);
      spec.has_look_at = true;
      spec.look_at = Eigen::Vector3d(la[0], la[1], la.size() == 3 ? la[2] : spec.position.z());
      if ((spec.look_at - spec.position).norm() < 0.1)
        w.fail(w.get("look_at"), path + ".look_at", "target closer than 0.1 m to the position");
    }
    spec.yaw_deg = w.number("yaw_deg", 0.0, -3600, 3600);
    spec.pitch_deg = w.number("pitch_deg", 0.0, -80, 80);
    spec.roll_deg = w.number("roll_deg", 0.0, -45, 45);
    spec.duration = w.number("duration", -1.0, 0.01, 600.0);
    if (i == 0 && w.has("duration"))
      w.fail(w.get("duration"), path + ".duration", "the first waypoint has no duration");
    spec.name = w.text("name", "");
    s.waypoints.push_back(spec);
  }
}

void parse_challenges(const Reader& top, Scenario& s, const std::string& file) {
  if (!top.has("challenges")) return;
  const YAML::Node cs = top.get("challenges");
  if (!cs.IsSequence()) top.fail(cs, "challenges", "must be a list");
  const int last = static_cast<int>(s.waypoints.size()) - 1;
  for (size_t i = 0; i < cs.size(); ++i) {
    const std::string path = "challenges[" + std::to_string(i) + "]";
    const Reader c(file, cs[i], path);
    c.allow_only({"kind", "from", "to", "strength"});
    ChallengeSpec spec;
    const std::string kind = c.choice("kind", "", kChallengeKinds, "challenge kind");
    spec.kind = static_cast<ChallengeKind>(std::find(kChallengeKinds.begin(), kChallengeKinds.end(), kind) -
                                           kChallengeKinds.begin());
    if (!c.has("from")) c.fail(cs[i], path + ".from", "missing (index of the waypoint where it begins)");
    spec.from = c.integer("from", 0, 0, last);
    if (!c.has("to")) c.fail(cs[i], path + ".to", "missing (index of the waypoint where it ends)");
    spec.to = c.integer("to", 0, 0, last);
    if (spec.to <= spec.from) c.fail(c.get("to"), path + ".to", "must be larger than 'from'");
    const double def = spec.kind == ChallengeKind::kDark ? 0.06 : 1.0;
    spec.strength = c.number("strength", def, 0.0, 5.0);
    s.challenges.push_back(spec);
  }
}

}  // namespace

Scenario parse_scenario(const std::string& yaml_text, const std::string& file_label) {
  YAML::Node root;
  try {
    root = YAML::Load(yaml_text);
  } catch (const YAML::ParserException& e) {
    throw InputError(file_label, "YAML syntax error: " + e.msg, e.mark.line + 1);
  }
  if (!root.IsMap()) throw InputError(file_label, "a scenario must be a YAML mapping with keys name, structure, path");
  const Reader top(file_label, root, "");
  top.allow_only({"name", "description", "platform", "jitter", "structure", "objects", "path", "challenges"});
  Scenario s;
  s.file = file_label;
  s.name = top.text("name", std::filesystem::path(file_label).stem().string());
  s.description = top.text("description", "");
  s.platform =
      top.choice("platform", "robot", {"robot", "drone"}, "platform") == "robot" ? Platform::kRobot : Platform::kDrone;
  if (top.has("jitter")) {
    const Reader j(file_label, top.get("jitter"), "jitter");
    j.allow_only({"position", "yaw_deg"});
    s.position_jitter = j.number("position", 0.05, 0.0, 1.0);
    s.yaw_jitter_deg = j.number("yaw_deg", 2.0, 0.0, 45.0);
  }
  parse_structure(top, s, file_label);
  parse_objects(top, s, file_label);
  parse_path(top, s, file_label);
  parse_challenges(top, s, file_label);
  return s;
}

Scenario load_scenario(const std::filesystem::path& file) {
  std::ifstream in(file);
  if (!in) throw InputError(file.string(), "cannot open scenario file");
  std::stringstream ss;
  ss << in.rdbuf();
  return parse_scenario(ss.str(), file.string());
}

}  // namespace wardmap::sim
