#include "semantics/detection/detector_factory.h"

#include "semantics/detection/annotations_detector.h"
#include "semantics/detection/dnn_detector.h"
#include "semantics/detection/model_description.h"
#include "semantics/detection/model_search.h"
#include "slam/core/errors.h"

namespace wardmap::semantics {

namespace fs = std::filesystem;

fs::path default_model_description(const std::string& kind) {
  if (kind == "yolox") return model_descriptions_dir() / "yolox-nano.yaml";
  if (kind == "nanodet") return model_descriptions_dir() / "nanodet-m.yaml";
  throw std::invalid_argument("no model description for detector kind '" + kind + "'");
}

std::unique_ptr<Detector> make_detector(const DetectorOptions& options, const fs::path& sequence_dir) {
  if (auto problem = options.validate()) throw InputError("detector options", *problem);
  if (options.kind == "annotations") {
    if (sequence_dir.empty())
      throw InputError("annotations.jsonl", "the annotations detector needs the sequence folder");
    return std::make_unique<AnnotationsDetector>(sequence_dir / "annotations.jsonl", options.noise);
  }
  const fs::path yaml =
      options.model_description.empty() ? default_model_description(options.kind) : options.model_description;
  ModelDescription model = load_model_description(yaml, options.models_dir);
  const fs::path weights = find_model_file(model.file, options.models_dir);
  DnnDetectorOptions dnn;
  dnn.score_threshold = static_cast<float>(options.score_threshold);
  dnn.nms_iou = static_cast<float>(options.nms_iou);
  dnn.landmark_set = options.landmark_set;
  return std::make_unique<DnnDetector>(std::move(model), weights, dnn);
}

}  // namespace wardmap::semantics
