// Object measurement L = {ID_obj, ID_kf, Box, Pose} (Assoc. Eq. 1), with the detector's class and
// score, the appearance embedding, and the 6-DoF pose with size in the world frame.
#pragma once

#include <Eigen/Core>
#include <optional>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "semantics/options.h"
#include "slam/core/camera.h"
#include "slam/core/se3.h"

namespace wardmap::semantics {

// Object frame: x across, y front to back, z up (the world's up); origin at the box centre.
struct ObjectPose {
  slam::SE3 pose;  // object-to-world
  Eigen::Vector3d size = Eigen::Vector3d::Zero();
};

struct ObjectMeasurement {
  int id = -1;          // ID_obj: index in the run's measurement list
  int keyframe = -1;    // ID_kf
  double timestamp = 0;
  Eigen::Vector4d box = Eigen::Vector4d::Zero();  // x0 y0 x1 y1
  std::string label;
  float score = 0;
  Eigen::VectorXf embedding;         // L2-normalised; empty when no embedder ran
  std::optional<ObjectPose> pose;    // empty: degenerate (no depth, too few points)
  int gt_instance = -1;              // true object id when the detector knows it (synthetic data)
};

// Assoc. Eq. 1 "Pose": the object's pose and size from the depth inside its box. Points are taken
// from the box shrunk by box_shrink, kept within depth_band of their median depth, moved to the
// world; the orientation is the principal horizontal axis (about `up`), the size the 5-95 %
// extents. With complete_depth_with_class_size, a centre seen only from the front is pushed back by
// half the missing depth of the class's typical size. Returns no pose rather than a wrong one.
// `occluders` are boxes of nearer detections of the same keyframe: their pixels are left out.
std::optional<ObjectPose> measure_pose_from_depth(const cv::Mat& depth, const slam::PinholeCamera& camera,
                                                  const slam::SE3& T_wc, const Eigen::Vector4d& box,
                                                  const Eigen::Vector3d& up, const std::string& label,
                                                  const SemanticOptions& options,
                                                  const std::vector<Eigen::Vector4d>& occluders = {});

// Median depth of the trimmed box (0 when it has no valid depth): orders a keyframe's detections
// front to back, so that each one is measured without the pixels of the nearer ones.
double box_median_depth(const cv::Mat& depth, const Eigen::Vector4d& box, const MeasurementOptions& options);

// For each box, the boxes of nearer detections overlapping it (Assoc. Eq. 1 measurements of one
// keyframe, measured front to back).
// `supports[i]` tells that detection i is of a class things stand on (a table): a much larger
// support box holding most of a box is not its occluder.
std::vector<std::vector<Eigen::Vector4d>> nearer_overlapping_boxes(const cv::Mat& depth,
                                                                   const std::vector<Eigen::Vector4d>& boxes,
                                                                   const MeasurementOptions& options,
                                                                   const std::vector<bool>& supports = {});

// The world's up direction from camera poses: the mean of their -y axes (cameras are held roughly
// upright), normalised.
Eigen::Vector3d estimate_up(const std::vector<slam::SE3>& camera_poses);

// A rotation with z along `up` and x along the horizontal direction of `axis` (canonical sign).
Eigen::Matrix3d upright_rotation(const Eigen::Vector3d& up, const Eigen::Vector3d& axis);

}  // namespace wardmap::semantics
