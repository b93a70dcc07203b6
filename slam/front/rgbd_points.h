// Map points from an RGB-D keyframe's depth. A new keyframe (ORB-SLAM's CreateNewKeyFrame): every
// keypoint without a point whose depth is below the close-depth threshold becomes a point, and at
// least `min_depth_points` of the nearest ones are created even beyond it. The first keyframe of a
// submap (ORB-SLAM's StereoInitialization): every keypoint with a depth becomes a point.
#pragma once

#include <memory>
#include <vector>

#include "slam/core/camera.h"
#include "slam/front/front_options.h"
#include "slam/front/key_frame.h"

namespace wardmap::slam {

class Submap;

// World position of keypoint i of features seen from pose T_wc (needs a depth).
Eigen::Vector3d unproject_keypoint(const FrameFeatures& f, size_t i, const SE3& T_wc, const PinholeCamera& camera);

// Creates the points, adds the keyframe's observation of each and returns them (for the frame too).
std::vector<std::pair<int, std::shared_ptr<MapPoint>>> create_depth_points(const std::shared_ptr<KeyFrame>& kf,
                                                                           Submap& submap, const PinholeCamera& camera,
                                                                           const TrackingOptions& options,
                                                                           bool every_depth = false);

}  // namespace wardmap::slam
