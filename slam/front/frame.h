// A tracking frame: ORB features with undistorted positions and depths, the map points matched to
// them and the estimated pose. Features are shared (immutable) with the keyframe built from it.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <memory>
#include <opencv2/core.hpp>
#include <vector>

#include "slam/core/camera.h"
#include "slam/core/se3.h"
#include "slam/front/feature_grid.h"
#include "slam/front/orb_extractor.h"

namespace wardmap::slam {

class MapPoint;
class KeyFrame;

struct FrameFeatures {
  std::vector<cv::KeyPoint> keypoints;  // distorted level-0 pixels, octave = level
  std::vector<Eigen::Vector2d> points;  // undistorted pixels
  std::vector<int> levels;
  std::vector<float> depth;    // metres; 0 = none
  std::vector<float> right_u;  // RGB-D as stereo: u - bf / depth; < 0 = none
  cv::Mat descriptors;         // N x 32 CV_8U
  FeatureGrid grid;
  const ScalePyramid* pyramid = nullptr;  // the extractor's (outlives every frame)
  double bf = 0;                          // virtual baseline x fx (pixels x metres)
  // The last flow_age.size() keypoints were not detected but followed by flow (Tracker, tracking.flow_extend / _mono):
  // frames each has been followed since its point was last matched to a detected keypoint.
  std::vector<int> flow_age;
  size_t detected() const { return keypoints.size() - flow_age.size(); }

  size_t size() const { return keypoints.size(); }
  const uchar* descriptor(size_t i) const { return descriptors.ptr<uchar>(static_cast<int>(i)); }
  bool has_depth(size_t i) const { return depth[i] > 0; }
};

// `image` as 8-bit grey (BGR, BGRA, grey of any depth).
cv::Mat to_grey(const cv::Mat& image);

// The depth (metres) at keypoint `pt` of pyramid scale `scale`; 0 when none, beyond `max_depth`, or
// on a silhouette (a neighbour `scale` pixels away differs by more than `max_depth_step` x depth).
float sample_keypoint_depth(const cv::Mat& depth, cv::Point2f pt, double scale, double max_depth,
                            double max_depth_step);

// Extracts ORB from `image` (grey or BGR) and samples `depth` (CV_32F metres, may be empty) at each
// keypoint; depths beyond `max_depth`, and depths that differ by more than `max_depth_step` x depth
// from the 8 neighbours at the keypoint's scale (silhouettes), are ignored.
std::shared_ptr<const FrameFeatures> make_frame_features(const cv::Mat& image, const cv::Mat& depth,
                                                         const OrbExtractor& extractor, const PinholeCamera& camera,
                                                         double virtual_baseline, double max_depth,
                                                         double max_depth_step);

class Frame {
 public:
  Frame(std::uint64_t id, double timestamp, std::shared_ptr<const FrameFeatures> features);

  std::uint64_t id() const { return id_; }
  double timestamp() const { return timestamp_; }
  const FrameFeatures& features() const { return *features_; }
  const std::shared_ptr<const FrameFeatures>& shared_features() const { return features_; }
  size_t size() const { return features_->size(); }

  const SE3& pose_cw() const { return T_cw_; }  // world to camera
  void set_pose_cw(const SE3& T_cw) { T_cw_ = T_cw; }
  Eigen::Vector3d camera_center() const { return T_cw_.inverse().translation(); }

  // Associations (same size as the features); null where unmatched.
  std::vector<std::shared_ptr<MapPoint>> map_points;
  std::vector<char> outlier;
  std::shared_ptr<KeyFrame> reference_keyframe;
  // tracking.flow_extend / _mono: the image pyramid (with gradients) of cv::buildOpticalFlowPyramid; else empty.
  std::vector<cv::Mat> flow_pyramid;
  cv::Mat depth;  // tracking.flow_extend and flow_depth, RGB-D: the frame's depth (CV_32F metres); else empty

  // Features with more keypoints appended (the first size() unchanged); new slots unmatched.
  void extend_features(std::shared_ptr<const FrameFeatures> features);

  int count_matches() const;
  // Drops the associations flagged as outliers (and clears the flags).
  void drop_outliers();

 private:
  std::uint64_t id_;
  double timestamp_;
  std::shared_ptr<const FrameFeatures> features_;
  SE3 T_cw_;
};

}  // namespace wardmap::slam
