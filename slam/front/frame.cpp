#include "slam/front/frame.h"

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>

#include "slam/front/map_point.h"

namespace wardmap::slam {

cv::Mat to_grey(const cv::Mat& image) {
  cv::Mat grey;
  if (image.channels() == 3)
    cv::cvtColor(image, grey, cv::COLOR_BGR2GRAY);
  else if (image.channels() == 4)
    cv::cvtColor(image, grey, cv::COLOR_BGRA2GRAY);
  else
    grey = image;
  if (grey.depth() != CV_8U) grey.convertTo(grey, CV_8U);
  return grey;
}

float sample_keypoint_depth(const cv::Mat& depth, cv::Point2f pt, double scale, double max_depth,
                            double max_depth_step) {
  const int u = cvRound(pt.x), v = cvRound(pt.y);
  if (u < 0 || v < 0 || u >= depth.cols || v >= depth.rows) return 0;
  const float d = depth.at<float>(v, u);
  if (!(d > 0 && d <= max_depth)) return 0;
  // A keypoint on a depth discontinuity (object silhouette) gets no depth: its 3-D point would
  // belong to either surface.
  // The window grows with the level: a coarse keypoint covers scale^level pixels.
  const int r = std::max(1, static_cast<int>(std::ceil(scale)));
  for (int dv = -r; dv <= r; dv += r)
    for (int du = -r; du <= r; du += r) {
      const int uu = std::clamp(u + du, 0, depth.cols - 1), vv = std::clamp(v + dv, 0, depth.rows - 1);
      const float dn = depth.at<float>(vv, uu);
      if (!(dn > 0) || std::abs(dn - d) > max_depth_step * d) return 0;
    }
  return d;
}

std::shared_ptr<const FrameFeatures> make_frame_features(const cv::Mat& image, const cv::Mat& depth,
                                                         const OrbExtractor& extractor, const PinholeCamera& camera,
                                                         double virtual_baseline, double max_depth,
                                                         double max_depth_step) {
  const cv::Mat grey = to_grey(image);
  OrbFeatures orb = extractor.extract(grey);
  auto f = std::make_shared<FrameFeatures>();
  f->keypoints = std::move(orb.keypoints);
  f->descriptors = orb.descriptors;
  f->pyramid = &extractor.pyramid();
  f->bf = virtual_baseline * camera.fx;
  const size_t n = f->keypoints.size();
  f->points.resize(n);
  f->levels.resize(n);
  f->depth.assign(n, 0.f);
  f->right_u.assign(n, -1.f);
  const bool has_depth = !depth.empty() && depth.type() == CV_32F;
  for (size_t i = 0; i < n; ++i) {
    const cv::KeyPoint& k = f->keypoints[i];
    const Eigen::Vector2d px(k.pt.x, k.pt.y);
    f->points[i] = camera.has_distortion() ? camera.undistort_point(px) : px;
    f->levels[i] = k.octave;
    if (!has_depth) continue;
    const float d = sample_keypoint_depth(depth, k.pt, f->pyramid->scale[static_cast<size_t>(k.octave)], max_depth,
                                          max_depth_step);
    if (d > 0) {
      f->depth[i] = d;
      f->right_u[i] = static_cast<float>(f->points[i].x() - f->bf / d);
    }
  }
  f->grid = FeatureGrid(f->points, f->levels, camera.width, camera.height);
  return f;
}

Frame::Frame(std::uint64_t id, double timestamp, std::shared_ptr<const FrameFeatures> features)
    : map_points(features->size()),
      outlier(features->size(), 0),
      id_(id),
      timestamp_(timestamp),
      features_(std::move(features)) {}

void Frame::extend_features(std::shared_ptr<const FrameFeatures> features) {
  features_ = std::move(features);
  map_points.resize(features_->size());
  outlier.resize(features_->size(), 0);
}

int Frame::count_matches() const {
  int n = 0;
  for (const auto& mp : map_points)
    if (mp && !mp->bad()) ++n;
  return n;
}

void Frame::drop_outliers() {
  for (size_t i = 0; i < map_points.size(); ++i)
    if (outlier[i]) {
      map_points[i].reset();
      outlier[i] = 0;
    }
}

}  // namespace wardmap::slam
