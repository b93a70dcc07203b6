#include "semantics/detection/detector_options.h"

#include <sstream>

#include "semantics/detection/yaml_keys.h"
#include "slam/core/errors.h"

namespace wardmap::semantics {

namespace {

std::optional<std::string> check(double v, double lo, double hi, const char* key) {
  if (v >= lo && v <= hi) return std::nullopt;
  std::ostringstream s;
  s << "'" << key << "' must be in [" << lo << ", " << hi << "], got " << v;
  return s.str();
}

}  // namespace

AnnotationNoise AnnotationNoise::none() {
  AnnotationNoise n;
  n.box_jitter = 0;
  n.miss_probability = 0;
  n.low_visible_miss_probability = 0;
  n.false_positives_per_frame = 0;
  n.confusion_probability = 0;
  n.score_std = 0;
  return n;
}

std::optional<std::string> DetectorOptions::validate() const {
  if (kind != "yolox" && kind != "nanodet" && kind != "annotations")
    return "'kind' must be one of yolox, nanodet, annotations, got '" + kind + "'";
  if (landmark_set != "hospital" && landmark_set != "road" && landmark_set != "indoor" && landmark_set != "coco")
    return "'landmark_set' must be one of hospital, road, indoor, coco, got '" + landmark_set + "'";
  const AnnotationNoise& n = noise;
  for (auto r :
       {check(score_threshold, 0, 1, "score_threshold"), check(nms_iou, 0, 1, "nms_iou"),
        check(n.box_jitter, 0, 1, "annotations.box_jitter"),
        check(n.miss_probability, 0, 1, "annotations.miss_probability"),
        check(n.low_visible_fraction, 0, 1, "annotations.low_visible_fraction"),
        check(n.low_visible_miss_probability, 0, 1, "annotations.low_visible_miss_probability"),
        check(n.false_positives_per_frame, 0, 20, "annotations.false_positives_per_frame"),
        check(n.confusion_probability, 0, 1, "annotations.confusion_probability"),
        check(n.min_visible, 0, 1, "annotations.min_visible"), check(n.score_base, 0, 1, "annotations.score_base"),
        check(n.score_visible_gain, 0, 1, "annotations.score_visible_gain"),
        check(n.score_std, 0, 1, "annotations.score_std"), check(n.image_width, 1, 1 << 16, "annotations.image_width"),
        check(n.image_height, 1, 1 << 16, "annotations.image_height")})
    if (r) return r;
  return std::nullopt;
}

DetectorOptions detector_options_from_yaml(const YAML::Node& section, const std::filesystem::path& file,
                                           const std::string& name) {
  using detail::yaml_read_optional;
  DetectorOptions o;
  if (!section) return o;
  if (!section.IsMap())
    throw InputError(file.string(), "key '" + name + "': expected a mapping", detail::yaml_line(section));
  yaml_read_optional(section, name, "kind", o.kind, file, "a string");
  yaml_read_optional(section, name, "score_threshold", o.score_threshold, file, "a number");
  yaml_read_optional(section, name, "nms_iou", o.nms_iou, file, "a number");
  std::string dir;
  yaml_read_optional(section, name, "models_dir", dir, file, "a path");
  if (!dir.empty()) o.models_dir = dir;
  std::string description;
  yaml_read_optional(section, name, "model_description", description, file, "a path");
  if (!description.empty()) o.model_description = description;
  yaml_read_optional(section, name, "landmark_set", o.landmark_set, file, "a string");
  const YAML::Node a = section["annotations"];
  const std::string p = name + ".annotations";
  AnnotationNoise& n = o.noise;
  yaml_read_optional(a, p, "seed", n.seed, file, "a non-negative integer");
  yaml_read_optional(a, p, "box_jitter", n.box_jitter, file, "a number");
  yaml_read_optional(a, p, "miss_probability", n.miss_probability, file, "a number");
  yaml_read_optional(a, p, "low_visible_fraction", n.low_visible_fraction, file, "a number");
  yaml_read_optional(a, p, "low_visible_miss_probability", n.low_visible_miss_probability, file, "a number");
  yaml_read_optional(a, p, "false_positives_per_frame", n.false_positives_per_frame, file, "a number");
  yaml_read_optional(a, p, "confusion_probability", n.confusion_probability, file, "a number");
  yaml_read_optional(a, p, "min_visible", n.min_visible, file, "a number");
  yaml_read_optional(a, p, "score_base", n.score_base, file, "a number");
  yaml_read_optional(a, p, "score_visible_gain", n.score_visible_gain, file, "a number");
  yaml_read_optional(a, p, "score_std", n.score_std, file, "a number");
  yaml_read_optional(a, p, "image_width", n.image_width, file, "an integer");
  yaml_read_optional(a, p, "image_height", n.image_height, file, "an integer");
  if (auto problem = o.validate()) throw InputError(file.string(), "key '" + name + "." + problem->substr(1));
  return o;
}

}  // namespace wardmap::semantics
