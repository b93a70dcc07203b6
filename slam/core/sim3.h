// Similarity transforms Sim(3): x -> s R x + t. Tangent vectors are [rho, phi, sigma] with s = e^sigma.
#pragma once

#include "slam/core/se3.h"

namespace wardmap::slam {

class Sim3 {
 public:
  Sim3() = default;
  Sim3(double scale, const Eigen::Quaterniond& q, const Eigen::Vector3d& t);
  explicit Sim3(const SE3& T) : Sim3(1.0, T.rotation(), T.translation()) {}

  static Sim3 exp(const Vector7d& xi);
  Vector7d log() const;

  Sim3 inverse() const;
  Sim3 operator*(const Sim3& o) const;
  Eigen::Vector3d operator*(const Eigen::Vector3d& p) const { return s_ * (q_ * p) + t_; }
  // Maps a camera-to-world pose through this transform of the world (keeps the pose rigid).
  SE3 transform_pose(const SE3& T) const { return SE3(q_ * T.rotation(), (*this) * T.translation()); }

  double scale() const { return s_; }
  const Eigen::Quaterniond& rotation() const { return q_; }
  const Eigen::Vector3d& translation() const { return t_; }
  Eigen::Matrix4d matrix() const;

 private:
  double s_ = 1.0;
  Eigen::Quaterniond q_ = Eigen::Quaterniond::Identity();
  Eigen::Vector3d t_ = Eigen::Vector3d::Zero();
};

}  // namespace wardmap::slam
