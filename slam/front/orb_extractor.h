// ORB features on a scale pyramid: FAST corners per level with a per-cell threshold fallback
// (iniThFAST, then minThFAST where a cell has none), a quadtree spread to the level's share of
// nFeatures, orientation by intensity centroid and rBRIEF descriptors (cv::ORB::compute on the
// given keypoints). Keypoints are returned in level-0 pixels, with `octave` = pyramid level.
#pragma once

#include <opencv2/core.hpp>
#include <opencv2/features2d.hpp>
#include <vector>

#include "slam/front/front_options.h"
#include "slam/front/scale_pyramid.h"

namespace wardmap::slam {

struct OrbFeatures {
  std::vector<cv::KeyPoint> keypoints;  // level-0 pixels (distorted), octave = level, angle in degrees
  cv::Mat descriptors;                  // N x 32, CV_8U
};

class OrbExtractor {
 public:
  explicit OrbExtractor(const OrbOptions& options);
  // `grey`: 8-bit single-channel image.
  OrbFeatures extract(const cv::Mat& grey) const;
  const ScalePyramid& pyramid() const { return pyramid_; }
  const OrbOptions& options() const { return options_; }

 private:
  std::vector<cv::Mat> build_pyramid(const cv::Mat& grey) const;
  std::vector<cv::KeyPoint> detect_level(const cv::Mat& level_image, int level) const;

  OrbOptions options_;
  ScalePyramid pyramid_;
  std::vector<int> features_per_level_;
  std::vector<int> circle_half_width_;  // half-width of the orientation patch per row offset
  cv::Ptr<cv::ORB> descriptor_;
};

// Orientation (degrees, [0, 360)) of the intensity centroid of the disc of radius `radius` around pt.
float intensity_centroid_angle(const cv::Mat& image, cv::Point2f pt, const std::vector<int>& half_width);

}  // namespace wardmap::slam
