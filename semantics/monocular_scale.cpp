#include "semantics/monocular_scale.h"

#include <algorithm>
#include <cmath>

#include "semantics/object_metrics.h"

namespace wardmap::semantics {

cv::Mat sparse_depth_image(const std::vector<Eigen::Vector3d>& points_cam, const slam::PinholeCamera& camera,
                           int radius, double scale) {
  cv::Mat depth(camera.height, camera.width, CV_32F, cv::Scalar(0));
  for (const Eigen::Vector3d& p : points_cam) {
    if (!(p.z() > 0) || !p.allFinite()) continue;
    const Eigen::Vector2d px = camera.project(p);
    if (!px.allFinite() || px.x() < -radius - 1 || px.y() < -radius - 1 || px.x() > camera.width + radius ||
        px.y() > camera.height + radius)
      continue;  // outside the image (also keeps the rounding below in range)
    const int u = static_cast<int>(std::lround(px.x())), v = static_cast<int>(std::lround(px.y()));
    const float z = static_cast<float>(p.z() * scale);
    for (int y = std::max(0, v - radius); y <= std::min(camera.height - 1, v + radius); ++y) {
      float* row = depth.ptr<float>(y);
      for (int x = std::max(0, u - radius); x <= std::min(camera.width - 1, u + radius); ++x)
        if (row[x] == 0 || z < row[x]) row[x] = z;
    }
  }
  return depth;
}

bool scale_class(const std::string& label, const SemanticOptions& options) {
  return options.monocular.scale_classes.count(label) > 0 && options.class_sizes.count(label) > 0;
}

std::optional<double> scale_estimate(const std::vector<Eigen::Vector3d>& points_cam, const slam::PinholeCamera& camera,
                                     const Eigen::Vector4d& box, const std::string& label,
                                     const SemanticOptions& options) {
  if (!scale_class(label, options)) return std::nullopt;
  const MeasurementOptions& m = options.measurement;
  const double h = box(3) - box(1), w = box(2) - box(0);
  if (h < m.min_box_side || w < m.min_box_side) return std::nullopt;
  if (box(1) <= m.border_margin || box(3) >= camera.height - 1 - m.border_margin) return std::nullopt;
  const double x0 = box(0) + m.box_shrink * w, x1 = box(2) - m.box_shrink * w;
  const double y0 = box(1) + m.box_shrink * h, y1 = box(3) - m.box_shrink * h;
  std::vector<double> z;
  for (const Eigen::Vector3d& p : points_cam) {
    if (!(p.z() > 0)) continue;
    const Eigen::Vector2d px = camera.project(p);
    if (px.x() >= x0 && px.x() <= x1 && px.y() >= y0 && px.y() <= y1) z.push_back(p.z());
  }
  if (static_cast<int>(z.size()) < options.monocular.min_points) return std::nullopt;
  const size_t k = static_cast<size_t>(std::floor(options.monocular.near_quantile * (z.size() - 1)));
  std::nth_element(z.begin(), z.begin() + static_cast<std::ptrdiff_t>(k), z.end());
  const double depth = z[k];
  // The box's height in map units at that depth (fy: the vertical focal length, undistorted pixels).
  const double height_units = h * depth / camera.fy;
  if (!(height_units > 0)) return std::nullopt;
  return options.class_sizes.at(label)[2] / height_units;
}

std::vector<double> keyframe_scale_estimates(const std::vector<Eigen::Vector3d>& points_cam,
                                             const slam::PinholeCamera& camera,
                                             const std::vector<Eigen::Vector4d>& boxes,
                                             const std::vector<std::string>& labels, const SemanticOptions& options) {
  std::vector<double> out;
  for (size_t i = 0; i < boxes.size(); ++i) {
    const Eigen::Vector4d& a = boxes[i];
    const double area = (a(2) - a(0)) * (a(3) - a(1));
    bool overlapped = false;
    for (size_t j = 0; j < boxes.size() && !overlapped; ++j)
      overlapped = j != i && box_intersection(a, boxes[j]) > options.monocular.max_box_overlap * area;
    if (overlapped) continue;
    if (auto e = scale_estimate(points_cam, camera, a, labels[i], options)) out.push_back(*e);
  }
  return out;
}

std::optional<double> metric_scale(std::vector<double> estimates, const MonocularOptions& options) {
  if (estimates.empty() || static_cast<int>(estimates.size()) < options.min_scale_estimates) return std::nullopt;
  const size_t mid = estimates.size() / 2;
  std::nth_element(estimates.begin(), estimates.begin() + static_cast<std::ptrdiff_t>(mid), estimates.end());
  return estimates[mid];
}

MeasurementOptions sparse_measurement_options(const SemanticOptions& options) {
  MeasurementOptions m = options.measurement;
  m.target_samples = 1 << 30;  // stride 1: a sparse image's pixels are too few to skip any
  const int side = 2 * options.monocular.point_radius + 1;
  m.min_points = options.monocular.min_points * side * side;
  // Each point fills a square of one depth, which faces the camera: its normals are not the
  // object's faces (a bed's axes would turn to the line of sight).
  m.axes_from_planes = false;
  return m;
}

}  // namespace wardmap::semantics
