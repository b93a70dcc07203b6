// A COCO detector run through OpenCV's dnn module on the CPU (YOLOX-nano, NanoDet-m), described by
// a ModelDescription: letterbox -> forward -> decode -> class->landmark mapping -> class-wise NMS ->
// boxes back in image pixels, clipped to the image.
#pragma once

#include <filesystem>
#include <opencv2/dnn.hpp>
#include <optional>
#include <string>
#include <vector>

#include "semantics/detection/detection.h"
#include "semantics/detection/model_description.h"
#include "semantics/detection/onnx_net.h"

namespace wardmap::semantics {

struct DnnDetectorOptions {
  float score_threshold = 0.35f;
  float nms_iou = 0.45f;
  std::string landmark_set = "indoor";  // a set of the description, or "coco" for raw class names
};

// Not thread-safe: detect() runs the one cv::dnn::Net it owns (make one detector per thread).
class DnnDetector : public Detector {
 public:
  // onnx_file: the weights (found through model_search.h). Throws InputError naming the file when
  // it cannot be read or lacks the outputs the description names.
  DnnDetector(ModelDescription model, const std::filesystem::path& onnx_file, const DnnDetectorOptions& options);

  std::vector<Detection> detect(const cv::Mat& image, double timestamp) override;
  std::string name() const override { return model_.name; }
  const ModelDescription& model() const { return model_; }

 private:
  ModelDescription model_;
  DnnDetectorOptions options_;
  std::vector<std::string> landmark_of_class_;  // "" = dropped in this landmark set
  std::vector<int> group_of_class_;             // NMS group: index of the landmark label
  cv::dnn::Net net_;
  OnnxRewrites rewrites_;  // YOLOX's Focus stage and output Transpose done in C++ (onnx_net.h)
  std::vector<std::string> output_names_;  // requested by name (NanoDet's unconnected order differs)
};

}  // namespace wardmap::semantics
