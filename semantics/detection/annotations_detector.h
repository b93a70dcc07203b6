// The annotations back-end: "detections" made from a synthetic sequence's ground-truth
// annotations.jsonl (FORMATS.md) through a seeded noise model, so the object pipeline can be tested
// against known answers with realistic imperfections.
//
// Per frame (matched by timestamp within 1e-4 s), per annotated object:
//   - not reported when visible < min_visible;
//   - missed with probability miss_probability, and additionally with low_visible_miss_probability
//     when visible < low_visible_fraction;
//   - label swapped for another hospital class with probability confusion_probability
//     (gt_instance keeps the true id);
//   - each box side moved by N(0, box_jitter * box width or height), then clipped to the image;
//   - score = score_base + score_visible_gain * visible + N(0, score_std), clamped to [0.01, 1].
// Plus Poisson(false_positives_per_frame) random boxes of a random hospital class (gt_instance -1).
// The same (seed, frame) always gives the same detections, whatever order frames come in.
// The score threshold and landmark set of DetectorOptions do not apply: labels in the annotations
// are landmark classes already.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "semantics/detection/detection.h"
#include "semantics/detection/detector_options.h"

namespace wardmap::semantics {

// The landmark classes of the synthetic hospital (used for confusions and false positives).
const std::vector<std::string>& hospital_classes();

struct AnnotatedObject {
  int id = -1;
  std::string label;
  Eigen::Vector4d box = Eigen::Vector4d::Zero();
  double visible = 1.0;
};

struct AnnotatedFrame {
  double timestamp = 0;
  std::vector<AnnotatedObject> objects;
};

// Reads annotations.jsonl; frames sorted by timestamp. Throws InputError(file, problem, line) for a
// malformed line, a missing field, or two frames closer than the matching tolerance.
std::vector<AnnotatedFrame> read_annotations(const std::filesystem::path& file);

class AnnotationsDetector : public Detector {
 public:
  // Matching tolerance between a requested timestamp and an annotated frame.
  static constexpr double kTimestampTolerance = 1e-4;

  AnnotationsDetector(const std::filesystem::path& annotations_file, const AnnotationNoise& noise);

  // image may be empty (then noise.image_width/height bound the false positives and nothing is
  // clipped). A timestamp with no annotated frame gives no detections (logged once as a warning).
  std::vector<Detection> detect(const cv::Mat& image, double timestamp) override;
  std::string name() const override { return "annotations"; }

  // The annotated frame within the tolerance, or nullptr.
  const AnnotatedFrame* find_frame(double timestamp) const;
  size_t num_frames() const { return frames_.size(); }

 private:
  std::filesystem::path file_;
  AnnotationNoise noise_;
  std::vector<AnnotatedFrame> frames_;
  bool warned_missing_ = false;
};

}  // namespace wardmap::semantics
