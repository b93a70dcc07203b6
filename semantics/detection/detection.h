// One object detection in one image, and the interface every detector back-end implements
// (YOLOX-nano, NanoDet-m, the synthetic-annotations back-end).
#pragma once

#include <Eigen/Core>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

namespace wardmap::semantics {

struct Detection {
  Eigen::Vector4d box = Eigen::Vector4d::Zero();  // x0, y0, x1, y1 in pixels of the input image
  std::string label;         // landmark class after mapping ("door", "chair", "vehicle", "tv", ...)
  std::string source_label;  // the detector's own class name ("car", "dining table")
  float score = 0;
  int gt_instance = -1;  // annotations back-end only: the true object id (-1 for false positives)
};

class Detector {
 public:
  virtual ~Detector() = default;
  // image: BGR 8-bit (grey and BGRA images are converted); timestamp identifies the frame (the
  // annotations back-end needs it; the network back-ends ignore it).
  virtual std::vector<Detection> detect(const cv::Mat& image, double timestamp) = 0;
  virtual std::string name() const = 0;
};

}  // namespace wardmap::semantics
