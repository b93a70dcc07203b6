// Object measurements on monocular SLAM keyframes (Assoc. Eq. 1 "Pose" from the keyframe's map
// points). A monocular map has no unit: the measurement rules and the association model are in
// metres (class sizes, depth windows, sigma_position). The map is brought to metres by a scale
// estimated from the detections themselves: the box height in pixels of an object whose box shows
// its height (monocular.scale_classes), at the depth of the map points inside the box, gives its
// height in map units; its class's typical height gives it in metres. The median over the run's
// detections is the scale.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <opencv2/core.hpp>

#include "semantics/options.h"
#include "slam/core/camera.h"

namespace wardmap::semantics {

// Depth image (CV_32F, 0 = no depth) of the camera-frame points (z > 0) seen by a keyframe: each
// point fills a (2 radius + 1)-pixel square around its projection, the nearest point where squares
// meet. `scale` multiplies the depths (map units to metres).
cv::Mat sparse_depth_image(const std::vector<Eigen::Vector3d>& points_cam, const slam::PinholeCamera& camera,
                           int radius, double scale = 1.0);

// Whether the class's box height is its height (monocular.scale_classes, with a typical size).
bool scale_class(const std::string& label, const SemanticOptions& options);

// One estimate of metres per map unit from one detection: the class's height over the box's height
// at the object's depth (the near_quantile of the depths of the points inside the trimmed box).
// None for other classes, boxes cut at the top or bottom border, or fewer than
// monocular.min_points points in the box.
std::optional<double> scale_estimate(const std::vector<Eigen::Vector3d>& points_cam, const slam::PinholeCamera& camera,
                                     const Eigen::Vector4d& box, const std::string& label,
                                     const SemanticOptions& options);

// The estimates of one keyframe's detections, leaving out the boxes another detection overlaps by
// more than monocular.max_box_overlap of their area (a chair behind a table shows only its back, its
// nearest points may lie on the table).
std::vector<double> keyframe_scale_estimates(const std::vector<Eigen::Vector3d>& points_cam,
                                             const slam::PinholeCamera& camera,
                                             const std::vector<Eigen::Vector4d>& boxes,
                                             const std::vector<std::string>& labels, const SemanticOptions& options);

// The median of the estimates; none with fewer than monocular.min_scale_estimates.
std::optional<double> metric_scale(std::vector<double> estimates, const MonocularOptions& options);

// The measurement options for a sparse depth image: every pixel of the trimmed box is read (no
// stride), the minimum number of samples is monocular.min_points squares' worth, and no axes come
// from face normals (each square faces the camera).
MeasurementOptions sparse_measurement_options(const SemanticOptions& options);

}  // namespace wardmap::semantics
