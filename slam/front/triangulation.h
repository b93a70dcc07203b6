// Two-view linear triangulation (DLT on normalised rays) and the checks a new map point must pass.
#pragma once

#include <optional>

#include "slam/core/se3.h"

namespace wardmap::slam {

// `x1`, `x2`: normalised rays (x, y, 1) in cameras 1 and 2; T1, T2: world-to-camera poses.
// Empty when the linear system is degenerate (point at infinity).
std::optional<Eigen::Vector3d> triangulate_dlt(const Eigen::Vector3d& x1, const Eigen::Vector3d& x2, const SE3& T1,
                                               const SE3& T2);

// Cosine of the angle between the two viewing rays of world point p from camera centres c1, c2.
inline double parallax_cos(const Eigen::Vector3d& p, const Eigen::Vector3d& c1, const Eigen::Vector3d& c2) {
  const Eigen::Vector3d r1 = p - c1, r2 = p - c2;
  return r1.dot(r2) / (r1.norm() * r2.norm());
}

}  // namespace wardmap::slam
