#include "semantics/detection/class_nms.h"

#include <algorithm>
#include <cmath>
#include <opencv2/dnn.hpp>
#include <stdexcept>

namespace wardmap::semantics {

std::vector<int> class_wise_nms(const std::vector<cv::Rect2d>& boxes, const std::vector<float>& scores,
                                const std::vector<int>& groups, float iou_threshold) {
  if (boxes.size() != scores.size() || boxes.size() != groups.size())
    throw std::invalid_argument("class_wise_nms: boxes, scores and groups differ in length");
  if (boxes.empty()) return {};
  double extent = 0;
  for (const auto& b : boxes)
    extent = std::max({extent, std::abs(b.x), std::abs(b.y), std::abs(b.br().x), std::abs(b.br().y)});
  const double offset = extent + 1.0;
  std::vector<cv::Rect2d> moved(boxes.size());
  for (size_t i = 0; i < boxes.size(); ++i) {
    moved[i] = boxes[i];
    moved[i].x += groups[i] * offset;
    moved[i].y += groups[i] * offset;
  }
  std::vector<int> keep;
  // Candidates were already thresholded; a score threshold of 0 keeps them all.
  cv::dnn::NMSBoxes(moved, scores, 0.0f, iou_threshold, keep);
  return keep;
}

}  // namespace wardmap::semantics
