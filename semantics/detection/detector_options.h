// Options of the detection module: which back-end, thresholds, where the models are, which
// class->landmark mapping, and the noise model of the annotations back-end. One struct, loaded from
// a YAML section and validated with messages that name the key and the allowed range.
#pragma once

#include <yaml-cpp/yaml.h>

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>

namespace wardmap::semantics {

// Noise model of the annotations back-end (annotations_detector.h). Defaults give a detector
// somewhat better than YOLOX-nano on clean synthetic frames.
struct AnnotationNoise {
  std::uint64_t seed = 1;                     // combined with each frame's timestamp
  double box_jitter = 0.03;                   // std of each box side, as a fraction of box width/height
  double miss_probability = 0.05;             // chance a reported object is missed
  double low_visible_fraction = 0.3;          // below this visible fraction misses get likelier ...
  double low_visible_miss_probability = 0.3;  // ... by this extra (independent) miss chance
  double false_positives_per_frame = 0.05;    // Poisson mean of random boxes per frame
  double confusion_probability = 0.01;        // chance the label is swapped for another hospital class
  double min_visible = 0.1;                   // objects less visible than this are never reported
  double score_base = 0.5;                    // score = score_base + score_visible_gain * visible + N(0, score_std)
  double score_visible_gain = 0.45;
  double score_std = 0.05;
  int image_width = 640;  // image size for false positives and clipping when detect() gets an empty image
  int image_height = 480;

  // All noise off: detections reproduce the annotations (visible >= min_visible) exactly.
  static AnnotationNoise none();
};

struct DetectorOptions {
  std::string kind = "yolox";               // yolox | nanodet | annotations
  double score_threshold = 0.35;            // network back-ends: candidates below are dropped
  double nms_iou = 0.45;                    // class-wise NMS IoU (MODELS.md)
  std::filesystem::path models_dir;         // searched first for weights (see model_search.h); empty = not set
  std::filesystem::path model_description;  // models/<kind>.yaml of the source tree when empty
  std::string landmark_set = "indoor";      // hospital | road | indoor | coco (raw COCO labels, no mapping)
  int embedding_threads = 2;                // OSNet copies embedding a keyframe's crops at once (Embedder)
  AnnotationNoise noise;                    // annotations back-end only

  // A message naming the first bad option and its allowed range, or nullopt.
  std::optional<std::string> validate() const;
};

// Reads a `detection:` style YAML section (keys as the field names above; the noise under
// `annotations:`); absent keys keep their defaults. Throws InputError(file, "key 'detection.x': ...").
DetectorOptions detector_options_from_yaml(const YAML::Node& section, const std::filesystem::path& file,
                                           const std::string& section_name = "detection");

}  // namespace wardmap::semantics
