#include "semantics/detection/model_description.h"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <fstream>
#include <initializer_list>
#include <set>

#include "semantics/detection/model_search.h"
#include "semantics/detection/yaml_keys.h"
#include "slam/core/errors.h"
#include "slam/io/settings.h"

namespace wardmap::semantics {

namespace fs = std::filesystem;
using detail::yaml_as;
using detail::yaml_line;
using detail::yaml_required;

namespace {

// A key of `n` outside `keys` (misspelt, "pad_valeu") is an error naming its line and the nearest
// key, rather than a default silently kept; prefix "" is the document's top level.
void reject_unknown_keys(const YAML::Node& n, const std::string& prefix, std::initializer_list<const char*> keys,
                         const fs::path& file) {
  slam::io::SectionKeys known(n, prefix, file);
  for (const char* k : keys) known.know(k);
  known.reject_unknown();
}

YAML::Node load_yaml(const fs::path& file) {
  if (!fs::is_regular_file(file)) throw InputError(file.string(), "model description not found");
  try {
    return YAML::LoadFile(file.string());
  } catch (const YAML::ParserException& ex) {
    throw InputError(file.string(), "YAML syntax error: " + ex.msg, ex.mark.line + 1);
  } catch (const YAML::Exception& ex) {
    throw InputError(file.string(), "cannot read: " + ex.msg);
  }
}

int positive_int(const YAML::Node& parent, const std::string& prefix, const std::string& key, const fs::path& file,
                 int max_value) {
  const YAML::Node n = yaml_required(parent, prefix, key, file);
  const int v = yaml_as<int>(n, prefix + "." + key, file, "an integer");
  if (v < 1 || v > max_value)
    throw InputError(
        file.string(),
        "key '" + prefix + "." + key + "': must be in [1, " + std::to_string(max_value) + "], got " + std::to_string(v),
        yaml_line(n));
  return v;
}

std::array<double, 3> triple(const YAML::Node& parent, const std::string& prefix, const std::string& key,
                             const fs::path& file, std::array<double, 3> fallback, bool positive) {
  const YAML::Node n = parent[key];
  if (!n) return fallback;
  const std::string full = prefix + "." + key;
  if (!n.IsSequence() || n.size() != 3)
    throw InputError(file.string(),
                     "key '" + full + "': expected a list of 3 numbers, got '" + detail::yaml_text(n) + "'",
                     yaml_line(n));
  std::array<double, 3> v{};
  for (size_t i = 0; i < 3; ++i) {
    v[i] = yaml_as<double>(n[i], full, file, "a list of 3 numbers");
    if (positive && !(v[i] > 0))
      throw InputError(file.string(), "key '" + full + "': every value must be > 0", yaml_line(n));
  }
  return v;
}

std::vector<std::string> string_list(const YAML::Node& parent, const std::string& prefix, const std::string& key,
                                     const fs::path& file) {
  const YAML::Node n = yaml_required(parent, prefix, key, file);
  const std::string full = prefix + "." + key;
  if (!n.IsSequence() || n.size() == 0)
    throw InputError(file.string(), "key '" + full + "': expected a non-empty list of names", yaml_line(n));
  std::vector<std::string> out;
  for (const auto& e : n) out.push_back(yaml_as<std::string>(e, full, file, "a list of names"));
  return out;
}

std::vector<std::string> read_class_list(const fs::path& file) {
  std::ifstream in(file);
  if (!in) throw InputError(file.string(), "cannot open the class list");
  std::vector<std::string> names;
  std::string line;
  long number = 0;
  while (std::getline(in, line)) {
    ++number;
    while (!line.empty() && (line.back() == '\r' || line.back() == ' ')) line.pop_back();
    if (line.empty()) throw InputError(file.string(), "empty class name", number);
    names.push_back(line);
  }
  if (names.empty()) throw InputError(file.string(), "the class list is empty");
  return names;
}

void read_input(const YAML::Node& root, const fs::path& file, InputSpec& in) {
  const YAML::Node n = yaml_required(root, "", "input", file);
  in.width = positive_int(n, "input", "width", file, 4096);
  in.height = positive_int(n, "input", "height", file, 4096);
  detail::yaml_read_optional(n, "input", "channel_order", in.channel_order, file, "a string");
  if (in.channel_order != "bgr" && in.channel_order != "rgb")
    throw InputError(file.string(), "key 'input.channel_order': must be bgr or rgb, got '" + in.channel_order + "'",
                     yaml_line(n["channel_order"]));
  in.mean = triple(n, "input", "mean", file, in.mean, false);
  in.std = triple(n, "input", "std", file, in.std, true);
  detail::yaml_read_optional(n, "input", "pad_value", in.pad_value, file, "a number");
  detail::yaml_read_optional(n, "input", "pad_after_normalisation", in.pad_after_normalisation, file, "true or false");
  detail::yaml_read_optional(n, "input", "canvas_multiple", in.canvas_multiple, file, "an integer");
  if (in.canvas_multiple < 0 || in.canvas_multiple > std::min(in.width, in.height))
    throw InputError(file.string(),
                     "key 'input.canvas_multiple': must be 0 (a fixed canvas) or in [1, " +
                         std::to_string(std::min(in.width, in.height)) + "], got " + std::to_string(in.canvas_multiple),
                     yaml_line(n["canvas_multiple"]));
  reject_unknown_keys(n, "input",
                      {"width", "height", "channel_order", "mean", "std", "pad_value", "pad_after_normalisation",
                       "canvas_multiple"},
                      file);
}

void read_output(const YAML::Node& root, const std::string& decoder, const fs::path& file, OutputSpec& out) {
  const YAML::Node n = yaml_required(root, "", "output", file);
  const YAML::Node strides = yaml_required(n, "output", "strides", file);
  if (!strides.IsSequence() || strides.size() == 0)
    throw InputError(file.string(), "key 'output.strides': expected a non-empty list of integers", yaml_line(strides));
  for (const auto& s : strides) {
    const int v = yaml_as<int>(s, "output.strides", file, "a list of integers");
    if (v < 1 || v > 1024)
      throw InputError(file.string(), "key 'output.strides': each stride must be in [1, 1024]", yaml_line(strides));
    out.strides.push_back(v);
  }
  out.names = string_list(n, "output", "names", file);
  if (decoder == "yolox" && out.names.size() != 1)
    throw InputError(file.string(), "key 'output.names': yolox has exactly one output", yaml_line(n["names"]));
  if (decoder == "nanodet") {
    out.box_names = string_list(n, "output", "box_names", file);
    if (out.names.size() != out.strides.size())
      throw InputError(file.string(), "key 'output.names': need one class output per stride", yaml_line(n["names"]));
    if (out.box_names.size() != out.strides.size())
      throw InputError(file.string(), "key 'output.box_names': need one box output per stride",
                       yaml_line(n["box_names"]));
    out.bins = positive_int(n, "output", "bins", file, 64);
    reject_unknown_keys(n, "output", {"strides", "names", "box_names", "bins"}, file);
  } else {
    reject_unknown_keys(n, "output", {"strides", "names"}, file);
  }
}

using LandmarkSets = std::map<std::string, std::map<std::string, std::string>>;

LandmarkSets read_landmark_sets(const YAML::Node& node, const fs::path& file, const std::string& prefix,
                                const std::vector<std::string>& classes) {
  if (!node.IsMap() || node.size() == 0)
    throw InputError(file.string(), "key '" + prefix + "': expected a mapping of landmark sets", yaml_line(node));
  const std::set<std::string> known(classes.begin(), classes.end());
  LandmarkSets sets;
  for (const auto& set : node) {
    const std::string set_name = yaml_as<std::string>(set.first, prefix, file, "a set name");
    const std::string set_key = prefix + "." + set_name;
    if (set_name == "coco")
      throw InputError(file.string(), "key '" + set_key + "': 'coco' is reserved (raw class names)",
                       yaml_line(set.first));
    if (!set.second.IsMap() || set.second.size() == 0)
      throw InputError(file.string(), "key '" + set_key + "': expected a mapping 'detector class: landmark class'",
                       yaml_line(set.second));
    auto& mapping = sets[set_name];
    for (const auto& entry : set.second) {
      const std::string from = yaml_as<std::string>(entry.first, set_key, file, "a class name");
      const std::string full = set_key + "." + from;
      if (!known.count(from))
        throw InputError(file.string(), "key '" + full + "': '" + from + "' is not in the model's class list",
                         yaml_line(entry.first));
      const std::string to = yaml_as<std::string>(entry.second, full, file, "a landmark class name");
      if (to.empty())
        throw InputError(file.string(), "key '" + full + "': empty landmark class", yaml_line(entry.second));
      mapping[from] = to;
    }
  }
  return sets;
}

// The file a description's `key` names (its class list, its landmark sets): an absolute path, or
// relative to the description's folder, then to the project's descriptions (models/), then to the
// models folders (model_search.h). So a description copied elsewhere to change one value still
// finds the shipped files. Not found: an error naming the key, its line and every place looked in.
fs::path referenced_file(const YAML::Node& root, const std::string& key, const fs::path& yaml_file,
                         const fs::path& models_dir) {
  const YAML::Node node = yaml_required(root, "", key, yaml_file);
  const fs::path name = yaml_as<std::string>(node, key, yaml_file, "a file name");
  std::vector<fs::path> places;
  if (name.is_absolute()) {
    places.push_back(name);
  } else {
    places = {yaml_file.parent_path() / name, model_descriptions_dir() / name};
    for (const fs::path& dir : model_search_path(models_dir)) places.push_back(dir / name);
  }
  std::string looked;
  for (const fs::path& place : places) {
    if (fs::is_regular_file(place)) return place;
    looked += (looked.empty() ? "" : ", ") + place.string();
  }
  throw InputError(yaml_file.string(), "key '" + key + "': file not found; looked in: " + looked, yaml_line(node));
}

}  // namespace

std::vector<std::string> ModelDescription::class_to_landmark(const std::string& set) const {
  std::vector<std::string> out(classes.size());
  if (set == "coco") return classes;
  const auto it = landmark_sets.find(set);
  if (it == landmark_sets.end()) {
    std::string have;
    for (const auto& [k, v] : landmark_sets) have += (have.empty() ? "" : ", ") + k;
    throw InputError(description_file.string(), "no landmark set '" + set + "' (have: " + have + ", coco)");
  }
  for (size_t i = 0; i < classes.size(); ++i)
    if (const auto m = it->second.find(classes[i]); m != it->second.end()) out[i] = m->second;
  return out;
}

ModelDescription load_model_description(const fs::path& yaml_file, const fs::path& models_dir) {
  const YAML::Node root = load_yaml(yaml_file);
  if (!root.IsMap()) throw InputError(yaml_file.string(), "expected a YAML mapping (see models/README.md)");
  reject_unknown_keys(root, "", {"name", "file", "decoder", "input", "output", "classes", "landmark_sets"}, yaml_file);
  ModelDescription d;
  d.description_file = yaml_file;
  d.name = yaml_as<std::string>(yaml_required(root, "", "name", yaml_file), "name", yaml_file, "a string");
  d.file = yaml_as<std::string>(yaml_required(root, "", "file", yaml_file), "file", yaml_file, "a path");
  if (d.file.empty()) throw InputError(yaml_file.string(), "key 'file': empty path", yaml_line(root["file"]));
  const YAML::Node decoder = yaml_required(root, "", "decoder", yaml_file);
  d.decoder = yaml_as<std::string>(decoder, "decoder", yaml_file, "a string");
  if (d.decoder != "yolox" && d.decoder != "nanodet")
    throw InputError(yaml_file.string(), "key 'decoder': must be yolox or nanodet, got '" + d.decoder + "'",
                     yaml_line(decoder));
  read_input(root, yaml_file, d.input);
  read_output(root, d.decoder, yaml_file, d.output);
  // Each output level is the input divided by its stride, cell for cell.
  const auto check_multiple = [&](const char* key, int value) {
    for (int s : d.output.strides)
      if (value % s != 0)
        throw InputError(yaml_file.string(),
                         std::string("key 'input.") + key + "': " + std::to_string(value) +
                             " is not a multiple of the output stride " + std::to_string(s),
                         yaml_line(root["input"][key]));
  };
  check_multiple("width", d.input.width);
  check_multiple("height", d.input.height);
  if (d.input.canvas_multiple > 0) check_multiple("canvas_multiple", d.input.canvas_multiple);

  d.classes = read_class_list(referenced_file(root, "classes", yaml_file, models_dir));

  const YAML::Node sets = yaml_required(root, "", "landmark_sets", yaml_file);
  if (sets.IsScalar()) {
    const fs::path sets_file = referenced_file(root, "landmark_sets", yaml_file, models_dir);
    // The shared file has the same shape as the inline form: a top-level `landmark_sets:` mapping.
    const YAML::Node shared = load_yaml(sets_file);
    reject_unknown_keys(shared, "", {"landmark_sets"}, sets_file);
    d.landmark_sets = read_landmark_sets(yaml_required(shared, "", "landmark_sets", sets_file), sets_file,
                                         "landmark_sets", d.classes);
  } else {
    d.landmark_sets = read_landmark_sets(sets, yaml_file, "landmark_sets", d.classes);
  }
  return d;
}

}  // namespace wardmap::semantics
