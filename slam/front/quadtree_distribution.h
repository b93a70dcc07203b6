// Spreads keypoints over an image region: the region is split into quadrants recursively until there
// are about `target` non-empty leaves, and each leaf keeps its strongest keypoint (ORB-SLAM's
// octree distribution).
#pragma once

#include <opencv2/core.hpp>
#include <vector>

namespace wardmap::slam {

// `keypoints` lie in `region` (pixel coordinates); returns at most max(target, leaves) keypoints.
std::vector<cv::KeyPoint> distribute_quadtree(const std::vector<cv::KeyPoint>& keypoints, const cv::Rect2f& region,
                                              int target);

}  // namespace wardmap::slam
