#include "slam/core/se3.h"

#include <Eigen/LU>
#include <cmath>

namespace wardmap::slam {

namespace {
constexpr double kSmallAngle = 1e-8;
}

Eigen::Matrix3d hat(const Eigen::Vector3d& v) {
  Eigen::Matrix3d m;
  m << 0, -v.z(), v.y(), v.z(), 0, -v.x(), -v.y(), v.x(), 0;
  return m;
}

Eigen::Matrix3d so3_exp(const Eigen::Vector3d& phi) {
  const double theta = phi.norm();
  if (theta < kSmallAngle) return Eigen::Matrix3d::Identity() + hat(phi);
  return Eigen::AngleAxisd(theta, phi / theta).toRotationMatrix();
}

Eigen::Vector3d so3_log(const Eigen::Matrix3d& R) {
  const Eigen::AngleAxisd aa(R);
  return aa.angle() * aa.axis();
}

SE3::SE3(const Eigen::Quaterniond& q, const Eigen::Vector3d& t) : q_(q.normalized()), t_(t) {}

SE3::SE3(const Eigen::Matrix3d& R, const Eigen::Vector3d& t) : q_(Eigen::Quaterniond(R).normalized()), t_(t) {}

SE3 SE3::from_matrix(const Eigen::Matrix4d& T) {
  // Project the rotation block onto SO(3) (files carry rounded values).
  Eigen::JacobiSVD<Eigen::Matrix3d> svd(T.topLeftCorner<3, 3>(), Eigen::ComputeFullU | Eigen::ComputeFullV);
  Eigen::Matrix3d R = svd.matrixU() * svd.matrixV().transpose();
  if (R.determinant() < 0) {
    Eigen::Matrix3d D = Eigen::Matrix3d::Identity();
    D(2, 2) = -1;
    R = svd.matrixU() * D * svd.matrixV().transpose();
  }
  return SE3(R, T.topRightCorner<3, 1>());
}

// Left Jacobian of SO(3): V(phi) with t = V rho.
static Eigen::Matrix3d so3_left_jacobian(const Eigen::Vector3d& phi) {
  const double theta = phi.norm();
  const Eigen::Matrix3d K = hat(phi);
  if (theta < 1e-5) return Eigen::Matrix3d::Identity() + 0.5 * K + K * K / 6.0;
  const double t2 = theta * theta;
  return Eigen::Matrix3d::Identity() + (1 - std::cos(theta)) / t2 * K + (theta - std::sin(theta)) / (t2 * theta) * K * K;
}

SE3 SE3::exp(const Vector6d& xi) {
  const Eigen::Vector3d rho = xi.head<3>(), phi = xi.tail<3>();
  return SE3(so3_exp(phi), so3_left_jacobian(phi) * rho);
}

Vector6d SE3::log() const {
  const Eigen::Vector3d phi = so3_log(rotation_matrix());
  Vector6d xi;
  xi.head<3>() = so3_left_jacobian(phi).inverse() * t_;
  xi.tail<3>() = phi;
  return xi;
}

SE3 SE3::inverse() const {
  const Eigen::Quaterniond qi = q_.conjugate();
  return SE3(qi, -(qi * t_));
}

Eigen::Matrix4d SE3::matrix() const {
  Eigen::Matrix4d T = Eigen::Matrix4d::Identity();
  T.topLeftCorner<3, 3>() = rotation_matrix();
  T.topRightCorner<3, 1>() = t_;
  return T;
}

SE3 SE3::interpolate(const SE3& a, const SE3& b, double s) {
  return SE3(a.q_.slerp(s, b.q_), (1 - s) * a.t_ + s * b.t_);
}

double rotation_angle(const Eigen::Quaterniond& q) {
  const double w = std::min(1.0, std::abs(q.normalized().w()));
  return 2.0 * std::acos(w);
}

}  // namespace wardmap::slam
