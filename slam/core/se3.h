// Rigid transforms SE(3) on Eigen: compose, inverse, exp/log, act on points, interpolate.
// Tangent vectors are ordered [rho (translation part), phi (rotation part)], as in Sophus.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace wardmap::slam {

using Vector6d = Eigen::Matrix<double, 6, 1>;
using Vector7d = Eigen::Matrix<double, 7, 1>;

// Skew-symmetric matrix of v, so that hat(v) * w == v.cross(w).
Eigen::Matrix3d hat(const Eigen::Vector3d& v);
// Rotation exponential (Rodrigues) and logarithm; the log is in [0, pi].
Eigen::Matrix3d so3_exp(const Eigen::Vector3d& phi);
Eigen::Vector3d so3_log(const Eigen::Matrix3d& R);

class SE3 {
 public:
  SE3() : q_(Eigen::Quaterniond::Identity()), t_(Eigen::Vector3d::Zero()) {}
  SE3(const Eigen::Quaterniond& q, const Eigen::Vector3d& t);
  SE3(const Eigen::Matrix3d& R, const Eigen::Vector3d& t);
  // From a 4x4 (or 3x4 top block) homogeneous matrix; the rotation block is re-orthonormalised.
  static SE3 from_matrix(const Eigen::Matrix4d& T);

  static SE3 exp(const Vector6d& xi);
  Vector6d log() const;

  SE3 inverse() const;
  SE3 operator*(const SE3& o) const { return SE3(q_ * o.q_, q_ * o.t_ + t_); }
  Eigen::Vector3d operator*(const Eigen::Vector3d& p) const { return q_ * p + t_; }

  const Eigen::Quaterniond& rotation() const { return q_; }
  Eigen::Matrix3d rotation_matrix() const { return q_.toRotationMatrix(); }
  const Eigen::Vector3d& translation() const { return t_; }
  Eigen::Matrix4d matrix() const;

  // Geodesic-free trajectory interpolation: slerp on rotation, linear on translation; s in [0, 1].
  static SE3 interpolate(const SE3& a, const SE3& b, double s);

 private:
  Eigen::Quaterniond q_;  // unit, w >= 0 not enforced
  Eigen::Vector3d t_;
};

// Angle of a rotation (radians, in [0, pi]).
double rotation_angle(const Eigen::Quaterniond& q);

}  // namespace wardmap::slam
