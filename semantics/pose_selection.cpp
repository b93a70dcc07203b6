#include "semantics/pose_selection.h"

#include <algorithm>
#include <cmath>

namespace wardmap::semantics {

double object_angle_difference(const slam::SE3& a, const slam::SE3& b) {
  const Eigen::Quaterniond d = a.rotation().conjugate() * b.rotation();
  const Eigen::Quaterniond half_turn(Eigen::AngleAxisd(M_PI, Eigen::Vector3d::UnitZ()));
  return std::min(slam::rotation_angle(d), slam::rotation_angle(d * half_turn));
}

// Assoc. Eq. 4 (angle) and Eq. 5 (distance): clipped at A and B, divided by them.
static double normalised(double value, double limit) { return value > limit ? 1.0 : value / limit; }

// Assoc. Eq. 6
std::vector<double> pose_differences(const std::vector<ObjectPose>& poses, const PoseSelectionOptions& o) {
  const size_t n = poses.size();
  std::vector<double> f(n, 0.0);
  if (n < 2) return f;
  const double A = o.max_angle_deg * M_PI / 180.0, B = o.max_distance;
  for (size_t k = 0; k < n; ++k) {
    double theta = 0, phi = 0;
    for (size_t l = 0; l < n; ++l) {
      if (l == k) continue;
      theta += normalised(object_angle_difference(poses[k].pose, poses[l].pose), A);
      phi += normalised((poses[k].pose.translation() - poses[l].pose.translation()).norm(), B);
    }
    f[k] = o.alpha * theta / (n - 1) + o.beta * phi / (n - 1);
  }
  return f;
}

int select_landmark_pose(const std::vector<ObjectPose>& poses, const PoseSelectionOptions& o) {
  if (poses.empty()) return -1;
  const std::vector<double> f = pose_differences(poses, o);
  return static_cast<int>(std::min_element(f.begin(), f.end()) - f.begin());
}

}  // namespace wardmap::semantics
