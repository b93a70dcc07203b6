// Class-wise non-maximum suppression. OpenCV 4.6 has no NMSBoxesBatched, so boxes of each group are
// moved apart by group * (largest coordinate + 1) before one cv::dnn::NMSBoxes call: boxes of
// different groups can then never overlap.
#pragma once

#include <opencv2/core.hpp>
#include <vector>

namespace wardmap::semantics {

// Indices of the kept boxes, best score first. groups[i] >= 0 is the class (or landmark) group.
std::vector<int> class_wise_nms(const std::vector<cv::Rect2d>& boxes, const std::vector<float>& scores,
                                const std::vector<int>& groups, float iou_threshold);

}  // namespace wardmap::semantics
