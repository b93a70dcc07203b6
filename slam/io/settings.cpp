#include "slam/io/settings.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <map>
#include <sstream>
#include <utility>
#include <vector>

#include "slam/core/errors.h"

namespace wardmap::slam::io {

namespace fs = std::filesystem;

namespace {

std::string strip_opencv_header(const std::string& text) {
  // OpenCV's FileStorage writes `%YAML:1.0`, which yaml-cpp rejects as a directive; blank it out
  // (keeping line numbers).
  if (text.rfind("%YAML:", 0) == 0) {
    const size_t eol = text.find('\n');
    return eol == std::string::npos ? std::string() : text.substr(eol);
  }
  return text;
}

template <class T>
bool read_key(const YAML::Node& root, const std::string& key, T& out, const fs::path& file, const char* expected) {
  const YAML::Node n = root[key];
  if (!n) return false;
  try {
    out = n.as<T>();
  } catch (const YAML::Exception&) {
    std::ostringstream v;
    v << n;
    throw InputError(file.string(), "key '" + key + "': expected " + expected + ", got '" + v.str() + "'", n.Mark().line + 1);
  }
  return true;
}

// The first of `keys` present; `used` is set to its name.
double required_number(const YAML::Node& root, std::initializer_list<const char*> keys, const fs::path& file,
                       std::string& used) {
  double v = 0;
  for (const char* k : keys)
    if (read_key(root, k, v, file, "a number")) {
      used = k;
      return v;
    }
  throw InputError(file.string(), std::string("missing key '") + *keys.begin() + "' (camera calibration)");
}

// A calibration the camera model refuses (`parameter` as PinholeCamera::validate names it), reported
// at the key that holds the wrong value (so that a --set override is blamed for its own value, and a
// file's line is given); the distortion coefficients, five keys, are reported without one.
[[noreturn]] void throw_calibration_error(const YAML::Node& root, const PinholeCamera& camera, const std::string& error,
                                          const std::string& parameter,
                                          const std::map<std::string, std::string>& keys, const fs::path& file) {
  std::string key;
  if (parameter == "size") {
    key = camera.width <= 0 ? "Camera.width" : "Camera.height";
  } else if (const auto k = keys.find(parameter); k != keys.end()) {  // "fx", "fy", "cx", "cy"
    key = k->second;
  }
  if (key.empty()) throw InputError(file.string(), "camera calibration: " + error);
  const YAML::Node n = root[key];
  throw InputError(file.string(), "key '" + key + "': camera calibration: " + error, n ? n.Mark().line + 1 : 0);
}

// yaml-cpp keeps the first of two equal keys of a mapping and silently ignores the other: a second
// `semantics:` section appended to a settings file would be lost. YAML forbids repeated keys.
void reject_repeated_keys(const YAML::Node& node, const std::string& path, const fs::path& file) {
  if (node.IsSequence())
    for (const auto& item : node) reject_repeated_keys(item, path, file);
  if (!node.IsMap()) return;
  std::map<std::string, int> first_line;
  for (const auto& kv : node) {
    if (!kv.first.IsScalar()) continue;
    const std::string key = kv.first.Scalar(), full = path.empty() ? key : path + "." + key;
    const int line = kv.first.Mark().line + 1;
    const auto [it, fresh] = first_line.emplace(key, line);
    if (!fresh)
      throw InputError(file.string(), "key '" + full + "' appears twice (lines " + std::to_string(it->second) + " and " +
                                          std::to_string(line) + "); merge the two, the second would be ignored",
                       line);
    reject_repeated_keys(kv.second, full, file);
  }
}

// The sections wardmap reads beside ORB-SLAM3's keys.
const char* const kSections[] = {"tracking", "mapping", "semantics", "detection"};

// The top-level keys wardmap reads (ORB-SLAM3's): parse_settings's camera keys, then
// load_front_options's ORBextractor and Stereo keys. A settings file may hold others (ORB-SLAM3's
// viewer, IMU...), which are ignored; a --set of one would change nothing, so it is refused.
// clang-format off
const char* const kTopLevelKeys[] = {
    "Camera.type", "Camera1.fx", "Camera1.fy", "Camera1.cx", "Camera1.cy", "Camera1.k1", "Camera1.k2", "Camera1.p1",
    "Camera1.p2", "Camera1.k3", "Camera.fx", "Camera.fy", "Camera.cx", "Camera.cy", "Camera.k1", "Camera.k2",
    "Camera.p1", "Camera.p2", "Camera.k3", "Camera.width", "Camera.height", "Camera.fps", "Camera.RGB",
    "RGBD.DepthMapFactor", "DepthMapFactor", "ORBextractor.nFeatures", "ORBextractor.scaleFactor",
    "ORBextractor.nLevels", "ORBextractor.iniThFAST", "ORBextractor.minThFAST", "Stereo.b", "Stereo.ThDepth",
    "Camera.bf", "ThDepth"};
// clang-format on

// ORB-SLAM3 keys wardmap does not read that are one letter from a key it does: not misspellings.
const char* const kNotMisspellings[] = {"Camera1.k4", "Camera.k4"};

// Keys read under two names, the first taken when a file has both (ORB-SLAM3's Camera1.fx over
// ORB-SLAM2's Camera.fx).
const std::pair<const char*, const char*> kAliases[] = {
    {"Camera1.fx", "Camera.fx"}, {"Camera1.fy", "Camera.fy"}, {"Camera1.cx", "Camera.cx"},
    {"Camera1.cy", "Camera.cy"}, {"Camera1.k1", "Camera.k1"}, {"Camera1.k2", "Camera.k2"},
    {"Camera1.p1", "Camera.p1"}, {"Camera1.p2", "Camera.p2"}, {"Camera1.k3", "Camera.k3"},
    {"RGBD.DepthMapFactor", "DepthMapFactor"}};

// Edit distance, for the suggestion in an unknown key's message.
size_t edit_distance(const std::string& a, const std::string& b) {
  std::vector<size_t> row(b.size() + 1);
  for (size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (size_t i = 1; i <= a.size(); ++i) {
    size_t diagonal = row[0];
    row[0] = i;
    for (size_t j = 1; j <= b.size(); ++j) {
      const size_t up = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] == b[j - 1] ? 0 : 1)});
      diagonal = up;
    }
  }
  return row[b.size()];
}

// The known key closest to `key` within `max_distance` edits (default: a third of its length, at
// least 3), else "".
template <class Keys>
std::string closest_key(const std::string& key, const Keys& known, size_t max_distance = 0) {
  std::string best;
  size_t best_distance = (max_distance > 0 ? max_distance : std::max<size_t>(3, key.size() / 3)) + 1;
  for (const auto& k : known) {
    const size_t d = edit_distance(key, k);
    if (d < best_distance) {
      best_distance = d;
      best = k;
    }
  }
  return best;
}

std::vector<std::string> split_dotted(const std::string& key) {
  std::vector<std::string> parts;
  for (size_t start = 0;;) {
    const size_t dot = key.find('.', start);
    parts.push_back(key.substr(start, dot == std::string::npos ? std::string::npos : dot - start));
    if (dot == std::string::npos) break;
    start = dot + 1;
  }
  return parts;
}

bool in_a_section(const std::string& key) {
  for (const char* section : kSections)
    if (key.rfind(std::string(section) + ".", 0) == 0) return true;
  return false;
}

// Sets root[a][b]...[last] = value for the dotted key "a.b. ... .last", creating the sections that
// are absent or written empty ("tracking:"). With `replace` false, a key already set is an error.
// Errors name `where` (the file, or --set) and `line`.
void set_dotted(YAML::Node& root, const std::string& key, const YAML::Node& value, bool replace, const std::string& where,
                int line) {
  const std::vector<std::string> parts = split_dotted(key);
  YAML::Node node = root;
  std::string path;
  for (size_t i = 0; i + 1 < parts.size(); ++i) {
    path = path.empty() ? parts[i] : path + "." + parts[i];
    if (parts[i].empty()) throw InputError(where, "key '" + key + "': empty part in a dotted key", line);
    YAML::Node child = node[parts[i]];
    if (!child || child.IsNull()) {
      node[parts[i]] = YAML::Node(YAML::NodeType::Map);
      child = node[parts[i]];
    }
    if (!child.IsMap()) throw InputError(where, "key '" + key + "': '" + path + "' is not a section", line);
    node.reset(child);
  }
  if (parts.back().empty()) throw InputError(where, "key '" + key + "': empty part in a dotted key", line);
  if (!replace && node[parts.back()])
    throw InputError(where, "key '" + key + "' is set twice: once dotted, once inside its section; keep one", line);
  node[parts.back()] = value;
}

// A top-level key written in the dotted form the documentation uses ("tracking.pose_solver: lm",
// "semantics.groups.size: 6") is moved into its section, as if it had been nested there. Setting
// the same key both ways is an error.
void nest_dotted_keys(YAML::Node& root, const fs::path& file) {
  std::vector<std::pair<std::string, YAML::Node>> dotted;
  for (const auto& kv : root)
    if (kv.first.IsScalar() && in_a_section(kv.first.Scalar())) dotted.emplace_back(kv.first.Scalar(), kv.second);
  for (auto& [key, value] : dotted) {
    const int line = root[key].Mark().line + 1;
    set_dotted(root, key, value, false, file.string(), line);
    root.remove(key);
  }
}

// A copy of a parsed node without its marks: errors about a --set value must not point at a line
// of the settings file.
YAML::Node without_marks(const YAML::Node& n) {
  if (n.IsScalar()) return YAML::Node(n.Scalar());
  YAML::Node out;
  if (n.IsSequence())
    for (const auto& item : n) out.push_back(without_marks(item));
  else if (n.IsMap())
    for (const auto& kv : n) out[kv.first.Scalar()] = without_marks(kv.second);
  return out;
}

}  // namespace

SettingOverride parse_setting_override(const std::string& text) {
  const size_t eq = text.find('=');
  if (eq == std::string::npos)
    throw InputError("--set", "'" + text + "': expected KEY=VALUE (e.g. tracking.flow_extend_mono=false)");
  SettingOverride o{text.substr(0, eq), text.substr(eq + 1)};
  if (o.key.empty()) throw InputError("--set", "'" + text + "': the key before '=' is empty");
  if (o.value.empty()) throw InputError("--set", "'" + text + "': the value after '=' is empty");
  for (const char* section : kSections)
    if (o.key == section)
      throw InputError("--set", "'" + text + "': '" + o.key + "' is a whole section; set its keys one by one (" + o.key +
                                    ".KEY=VALUE)");
  if (!in_a_section(o.key) &&
      std::find_if(std::begin(kTopLevelKeys), std::end(kTopLevelKeys), [&](const char* k) { return o.key == k; }) ==
          std::end(kTopLevelKeys)) {
    std::vector<std::string> known(std::begin(kTopLevelKeys), std::end(kTopLevelKeys));
    for (const char* section : kSections) known.push_back(std::string(section) + ".");
    const std::string best = closest_key(o.key, known);
    throw InputError("--set", "'" + text + "': '" + o.key + "' is not a key wardmap reads" +
                                  (best.empty() ? std::string() : " (did you mean '" + best + "'?)") +
                                  "; its own keys are tracking.*, mapping.*, semantics.* and detection.*");
  }
  return o;
}

void apply_setting_overrides(YAML::Node& root, const std::vector<SettingOverride>& overrides) {
  for (const SettingOverride& o : overrides) {
    YAML::Node value;
    try {
      value = without_marks(YAML::Load(o.value));
    } catch (const YAML::ParserException& ex) {
      throw InputError("--set", "'" + o.key + "=" + o.value + "': the value is not valid YAML: " + ex.msg);
    }
    if (in_a_section(o.key)) {
      set_dotted(root, o.key, value, true, "--set", 0);
      continue;
    }
    for (const auto& [preferred, other] : kAliases)  // the file's preferred name would hide this one
      if (o.key == other && static_cast<const YAML::Node&>(root)[preferred])
        throw InputError("--set", "'" + o.key + "=" + o.value + "': the settings file writes this key as '" + preferred +
                                      "', which is read first; set that one");
    root[o.key] = value;  // an ORB-SLAM3 key ("ORBextractor.nFeatures", "Camera1.fx"): dots are part of it
  }
}

void blame_overrides(const std::vector<SettingOverride>& overrides, const std::function<void()>& load) {
  try {
    load();
  } catch (const InputError& e) {
    const std::string what = e.what();
    for (const SettingOverride& o : overrides)
      if (what.find("key '" + o.key + "'") != std::string::npos) {
        const size_t colon = what.find(": ", e.file().size());
        throw InputError("--set " + o.key + "=" + o.value, colon == std::string::npos ? what : what.substr(colon + 2));
      }
    throw;
  }
}

std::optional<std::string> fit_calibration_size(PinholeCamera& camera, int width, int height, const std::string& source,
                                                const std::vector<SettingOverride>& overrides,
                                                const std::string& size_keys) {
  if (camera.width == width && camera.height == height) return std::nullopt;
  std::string blamed = source;
  for (const SettingOverride& o : overrides)
    if ((o.key == "Camera.width" && camera.width != width) || (o.key == "Camera.height" && camera.height != height))
      blamed = "--set " + o.key + "=" + o.value;
  const std::string sizes = size_keys + " " + std::to_string(camera.width) + "x" + std::to_string(camera.height);
  const std::string images = "the sequence's images " + std::to_string(width) + "x" + std::to_string(height);
  const auto near = [](int a, int b) {
    return std::abs(a - b) <= std::max<double>(kCalibrationSizeTolerancePixels, kCalibrationSizeTolerance * b);
  };
  if (!near(camera.width, width) || !near(camera.height, height))
    throw InputError(blamed, sizes + " do not match " + images);
  PinholeCamera fitted = camera;
  fitted.width = width;
  fitted.height = height;
  if (auto err = fitted.validate())
    throw InputError(blamed, sizes + " are close to " + images + ", but on them: " + *err);
  camera = fitted;
  return blamed + ": " + sizes + " differ slightly from " + images +
         " (by at most 2 % or 2 pixels a side): the images' size is used";
}

namespace {

std::array<double, 5> distortion_of(const PinholeCamera& c) { return {c.k1, c.k2, c.p1, c.p2, c.k3}; }

}  // namespace

std::string describe_intrinsics(const PinholeCamera& c, bool with_distortion) {
  char buf[256];
  int n = std::snprintf(buf, sizeof buf, "fx %.3f fy %.3f cx %.3f cy %.3f", c.fx, c.fy, c.cx, c.cy);
  if (with_distortion && n > 0 && static_cast<size_t>(n) < sizeof buf)
    std::snprintf(buf + n, sizeof buf - static_cast<size_t>(n), " k1 %g k2 %g p1 %g p2 %g k3 %g", c.k1, c.k2, c.p1,
                  c.p2, c.k3);
  return buf;
}

std::optional<std::string> calibration_disagreement(const PinholeCamera& used, const std::string& used_source,
                                                    const PinholeCamera& carried, const std::string& carried_source) {
  const auto focal_off = [](double a, double b) { return std::abs(a - b) > kCalibrationFocalTolerance * std::abs(b); };
  const auto centre_off = [](double a, double b) { return std::abs(a - b) > kCalibrationCentreTolerancePixels; };
  bool differs = focal_off(used.fx, carried.fx) || focal_off(used.fy, carried.fy) || centre_off(used.cx, carried.cx) ||
                 centre_off(used.cy, carried.cy);
  const auto du = distortion_of(used), dc = distortion_of(carried);
  for (size_t i = 0; i < du.size(); ++i) differs = differs || std::abs(du[i] - dc[i]) > kCalibrationDistortionTolerance;
  if (!differs) return std::nullopt;
  const bool with_distortion = used.has_distortion() || carried.has_distortion();
  return used_source + ": the camera (" + describe_intrinsics(used, with_distortion) +
         ") differs from the calibration the sequence carries (" + carried_source + ": " +
         describe_intrinsics(carried, with_distortion) + "); the settings' camera is used";
}

std::optional<std::string> depth_factor_disagreement(double used, const std::string& used_source, double format_factor,
                                                     const std::string& format) {
  if (format_factor <= 0 || std::abs(used - format_factor) <= 0.01 * format_factor) return std::nullopt;
  char buf[160];
  std::snprintf(buf, sizeof buf, ": RGBD.DepthMapFactor %g differs from the %g raw units per metre of the ", used,
                format_factor);
  return used_source + buf + format + " format; the settings' factor is used";
}

namespace {

// Settings::notes for the top-level keys not read that look meant to change something, and an
// error for a mapping named like one of wardmap's sections ("Tracking:", "trackingg:"), whose keys
// would all be ignored. ORB-SLAM3's other keys (Viewer.*, IMU.*, matrices) pass without a word.
std::vector<std::string> unread_key_notes(const YAML::Node& root, const CameraSettings& c, const fs::path& file) {
  std::vector<std::string> notes;
  bool second_camera = false;
  for (const auto& kv : root) {
    if (!kv.first.IsScalar()) continue;
    const std::string key = kv.first.Scalar();
    const auto listed = [&](const auto& keys) {
      return std::find(std::begin(keys), std::end(keys), key) != std::end(keys);
    };
    if (listed(kTopLevelKeys) || listed(kSections) || listed(kNotMisspellings)) continue;
    const int line = kv.first.Mark().line + 1;
    const std::string at = file.string() + (line > 0 ? ":" + std::to_string(line) : "") + ": key '" + key + "'";
    const auto number = [&] { return kv.second.IsScalar() ? std::strtod(kv.second.Scalar().c_str(), nullptr) : 0.0; };
    if (key.rfind("Camera2.", 0) == 0) {
      if (!second_camera)
        notes.push_back(at +
                        ": a stereo rig's second camera (Camera2.*) is not read; wardmap runs monocular or RGB-D "
                        "on Camera1");
      second_camera = true;
    } else if ((key == "Camera.imageScale" && number() != 1) ||
               (key == "Camera.newWidth" && number() != c.camera.width) ||
               (key == "Camera.newHeight" && number() != c.camera.height)) {
      notes.push_back(at +
                      ": ORB-SLAM3 resizes the images by it; wardmap does not read it and tracks the images at "
                      "their own size with Camera1's calibration");
    } else if (kv.second.IsMap()) {
      const std::string section = kv.second["data"] ? "" : closest_key(key, kSections);  // "data": an OpenCV matrix
      if (!section.empty())
        throw InputError(file.string(),
                         "key '" + key + "': not a section wardmap reads (did you mean '" + section +
                             "'?); its keys would all be ignored",
                         line);
    } else if (const std::string best = closest_key(key, kTopLevelKeys, 2); !best.empty()) {
      notes.push_back(at + ": not a key wardmap reads, so it changes nothing (did you mean '" + best + "'?)");
    }
  }
  return notes;
}

}  // namespace

Settings parse_settings(const std::string& text, const fs::path& file, const std::vector<SettingOverride>& overrides) {
  Settings s;
  s.file = file;
  try {
    s.root = YAML::Load(strip_opencv_header(text));
  } catch (const YAML::ParserException& ex) {
    throw InputError(file.string(), "YAML syntax error: " + ex.msg, ex.mark.line + 1);
  }
  if (!s.root.IsMap()) throw InputError(file.string(), "expected a YAML mapping of settings");
  reject_repeated_keys(s.root, "", file);
  nest_dotted_keys(s.root, file);
  apply_setting_overrides(s.root, overrides);
  const YAML::Node& r = s.root;
  CameraSettings& c = s.camera;
  read_key(r, "Camera.type", c.type, file, "a string");
  if (c.type != "PinHole")
    throw InputError(file.string(), "key 'Camera.type': '" + c.type + "' is not supported (allowed: PinHole)");
  std::map<std::string, std::string> camera_keys;  // "fx" -> the key it was read from
  c.camera.fx = required_number(r, {"Camera1.fx", "Camera.fx"}, file, camera_keys["fx"]);
  c.camera.fy = required_number(r, {"Camera1.fy", "Camera.fy"}, file, camera_keys["fy"]);
  c.camera.cx = required_number(r, {"Camera1.cx", "Camera.cx"}, file, camera_keys["cx"]);
  c.camera.cy = required_number(r, {"Camera1.cy", "Camera.cy"}, file, camera_keys["cy"]);
  for (auto [k3, k2, dst] : {std::tuple{"Camera1.k1", "Camera.k1", &c.camera.k1}, {"Camera1.k2", "Camera.k2", &c.camera.k2},
                             {"Camera1.p1", "Camera.p1", &c.camera.p1}, {"Camera1.p2", "Camera.p2", &c.camera.p2},
                             {"Camera1.k3", "Camera.k3", &c.camera.k3}})
    if (!read_key(r, k3, *dst, file, "a number")) read_key(r, k2, *dst, file, "a number");
  if (!read_key(r, "Camera.width", c.camera.width, file, "an integer"))
    throw InputError(file.string(), "missing key 'Camera.width'");
  if (!read_key(r, "Camera.height", c.camera.height, file, "an integer"))
    throw InputError(file.string(), "missing key 'Camera.height'");
  std::string bad_parameter;
  if (auto err = c.camera.validate(&bad_parameter))
    throw_calibration_error(r, c.camera, *err, bad_parameter, camera_keys, file);
  read_key(r, "Camera.fps", c.fps, file, "a number");
  if (!(c.fps > 0 && c.fps <= 1000)) throw InputError(file.string(), "key 'Camera.fps': must be in (0, 1000], got " + std::to_string(c.fps));
  int rgb = 1;
  if (read_key(r, "Camera.RGB", rgb, file, "0 or 1") && rgb != 0 && rgb != 1)
    throw InputError(file.string(), "key 'Camera.RGB': must be 0 or 1, got " + std::to_string(rgb));
  c.rgb = rgb == 1;
  double factor = 0;
  if (read_key(r, "RGBD.DepthMapFactor", factor, file, "a number") || read_key(r, "DepthMapFactor", factor, file, "a number")) {
    if (!(factor > 0)) throw InputError(file.string(), "key 'RGBD.DepthMapFactor': must be positive, got " + std::to_string(factor));
    c.depth_map_factor = factor;
  }
  s.notes = unread_key_notes(r, c, file);
  return s;
}

Settings load_settings(const fs::path& file, const std::vector<SettingOverride>& overrides) {
  if (!fs::exists(file)) throw InputError(file.string(), "settings file not found");
  std::ifstream in(file);
  if (!in) throw InputError(file.string(), "cannot open the settings file");
  std::stringstream ss;
  ss << in.rdbuf();
  return parse_settings(ss.str(), file, overrides);
}

namespace {
std::string full(const std::string& s, const std::string& k) { return s.empty() ? k : s + "." + k; }
}  // namespace

// NOLINTBEGIN(bugprone-macro-parentheses): T is a type
#define WARDMAP_READ_OPTION(T, expected)                                                                         \
  void read_option(const YAML::Node& section, const std::string& section_name, const std::string& key, T& value, \
                   const fs::path& file) {                                                                       \
    if (!section || !section.IsMap() || !section[key]) return;                                                  \
    try {                                                                                                        \
      value = section[key].as<T>();                                                                              \
    } catch (const YAML::Exception&) {                                                                           \
      std::ostringstream v;                                                                                      \
      v << section[key];                                                                                         \
      throw InputError(file.string(), "key '" + full(section_name, key) + "': expected " expected ", got '" +   \
                                          v.str() + "'", section[key].Mark().line + 1);                          \
    }                                                                                                            \
  }
WARDMAP_READ_OPTION(double, "a number")
WARDMAP_READ_OPTION(int, "an integer")
WARDMAP_READ_OPTION(bool, "true or false")
WARDMAP_READ_OPTION(std::string, "a string")
WARDMAP_READ_OPTION(std::uint64_t, "a non-negative integer")
#undef WARDMAP_READ_OPTION
// NOLINTEND(bugprone-macro-parentheses)

void check_range(double value, double lo, double hi, const std::string& full_key, const fs::path& file) {
  if (!(value >= lo && value <= hi)) {
    std::ostringstream s;
    s << "key '" << full_key << "': must be in [" << lo << ", " << hi << "], got " << value;
    throw InputError(file.string(), s.str());
  }
}

std::string suggest_settings_name(const std::string& kind, const fs::path& root, int width) {
  const std::string name = root.filename().string() + " " + root.parent_path().filename().string();
  if (kind == "KITTI odometry") {
    if (width == 1241) return "KITTI00-02.yaml";
    if (width == 1242) return "KITTI03.yaml";
    if (width == 1226) return "KITTI04-12.yaml";
  }
  if (kind == "7-Scenes") return "7Scenes.yaml";
  if (kind == "EuRoC") return "EuRoC.yaml";
  if (kind == "TUM RGB-D") {
    if (name.find("freiburg1") != std::string::npos || name.find("fr1") != std::string::npos) return "TUM1.yaml";
    if (name.find("freiburg2") != std::string::npos || name.find("fr2") != std::string::npos) return "TUM2.yaml";
    if (name.find("freiburg3") != std::string::npos || name.find("fr3") != std::string::npos) return "TUM3.yaml";
  }
  return {};
}

SectionKeys::SectionKeys(const YAML::Node& section, std::string name, fs::path file)
    : section_(section), name_(std::move(name)), file_(std::move(file)) {}

void SectionKeys::reject_unknown() const {
  if (!section_ || section_.IsNull()) return;  // absent, or written empty ("tracking:")
  if (!section_.IsMap())
    throw InputError(file_.string(), "key '" + name_ + "': expected a section (a mapping of keys)",
                     section_.Mark().line + 1);
  for (const auto& kv : section_) {
    const std::string key = kv.first.Scalar();
    if (std::find(known_.begin(), known_.end(), key) != known_.end()) continue;
    const std::string best = closest_key(key, known_);
    std::string message = "key '" + full(name_, key) + "': " +
                          (name_.empty() ? std::string("not a known key") : "not a key of section '" + name_ + "'");
    if (!best.empty()) message += " (did you mean '" + full(name_, best) + "'?)";
    throw InputError(file_.string(), message, kv.first.Mark().line + 1);
  }
}

}  // namespace wardmap::slam::io
