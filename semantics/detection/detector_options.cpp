#include "semantics/detection/detector_options.h"

#include <sstream>

#include "slam/core/errors.h"
#include "slam/io/settings.h"

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
        check(embedding_threads, 1, 8, "embedding_threads"),
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
  DetectorOptions o;
  slam::io::SectionKeys dk(section, name, file);
  dk.read("kind", o.kind);
  dk.read("score_threshold", o.score_threshold);
  dk.read("nms_iou", o.nms_iou);
  std::string dir = o.models_dir.string(), description = o.model_description.string();
  dk.read("models_dir", dir);
  dk.read("model_description", description);
  o.models_dir = dir;
  o.model_description = description;
  dk.read("landmark_set", o.landmark_set);
  dk.read("embedding_threads", o.embedding_threads);
  slam::io::SectionKeys ak = dk.section("annotations");
  AnnotationNoise& n = o.noise;
  ak.read("seed", n.seed);
  ak.read("box_jitter", n.box_jitter);
  ak.read("miss_probability", n.miss_probability);
  ak.read("low_visible_fraction", n.low_visible_fraction);
  ak.read("low_visible_miss_probability", n.low_visible_miss_probability);
  ak.read("false_positives_per_frame", n.false_positives_per_frame);
  ak.read("confusion_probability", n.confusion_probability);
  ak.read("min_visible", n.min_visible);
  ak.read("score_base", n.score_base);
  ak.read("score_visible_gain", n.score_visible_gain);
  ak.read("score_std", n.score_std);
  ak.read("image_width", n.image_width);
  ak.read("image_height", n.image_height);
  dk.reject_unknown();
  ak.reject_unknown();
  if (auto problem = o.validate()) throw InputError(file.string(), "key '" + name + "." + problem->substr(1));
  return o;
}

}  // namespace wardmap::semantics
