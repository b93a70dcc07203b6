// ORB features on a scale pyramid: FAST corners per level with a per-cell threshold fallback
// (iniThFAST, then minThFAST where a cell has none), a quadtree spread to the level's share of
// nFeatures, orientation by intensity centroid and rBRIEF descriptors on the Gaussian-smoothed
// level (bit for bit what cv::ORB::compute gives for the same keypoints). Keypoints are returned in
// level-0 pixels, with `octave` = pyramid level.
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
  // The pyramid `extract` works on: level l is level l-1 resized (bilinear) to the image's size
  // divided by scale_factor^l, rounded. Any image type cv::resize takes.
  std::vector<cv::Mat> build_pyramid(const cv::Mat& grey) const;

 private:
  std::vector<cv::KeyPoint> detect_level(const cv::Mat& level_image, int level) const;
  // Keypoints of one level (level pixels) and their descriptors.
  std::vector<cv::KeyPoint> extract_level(const cv::Mat& level_image, int level, cv::Mat& descriptors) const;
  // intensity_centroid_angle with this extractor's disc (radius 15), vectorised where it can be.
  float centroid_angle(const cv::Mat& level_image, cv::Point2f pt) const;

  OrbOptions options_;
  ScalePyramid pyramid_;
  std::vector<int> features_per_level_;
  std::vector<int> circle_half_width_;  // half-width of the orientation patch per row offset
};

// A pixel position on a pyramid level of size `level` in the pixels of the `image`-sized level 0.
// cv::resize maps pixel centres, x0 = (x + 0.5) r - 0.5, with r the ratio of the sizes it was given
// (the level's rounded width and height, not scale_factor^l: at 640x480 they differ by up to 0.2 %
// at level 7, 1.4 px at the right border).
cv::Point2f level_to_image(cv::Point2f p, cv::Size level, cv::Size image);

// Orientation (degrees, [0, 360)) of the intensity centroid of the disc of radius `radius` around pt.
float intensity_centroid_angle(const cv::Mat& image, cv::Point2f pt, const std::vector<int>& half_width);

// The smoothing rBRIEF samples: a 7x7 Gaussian of sigma 2 (BORDER_REFLECT_101), rounded as cv::ORB's.
void smooth_level(const cv::Mat& level, cv::Mat& blurred);

// rBRIEF (the 256-pair ORB pattern, 31x31 patch, steered by each keypoint's angle) of `keypoints`
// (pixels of `blurred`, at least 19 pixels from its border) into rows first_row.. of `descriptors`
// (N x 32, CV_8U). `blurred` comes from smooth_level.
void compute_orb_descriptors(const cv::Mat& blurred, const std::vector<cv::KeyPoint>& keypoints,
                             cv::Mat& descriptors, int first_row = 0);

}  // namespace wardmap::slam
