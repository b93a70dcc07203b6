#include "slam/core/sim3.h"

#include <stdexcept>
#include <unsupported/Eigen/MatrixFunctions>

namespace wardmap::slam {

Sim3::Sim3(double scale, const Eigen::Quaterniond& q, const Eigen::Vector3d& t) : s_(scale), q_(q.normalized()), t_(t) {
  if (!(scale > 0)) throw std::invalid_argument("Sim3: scale must be positive");
}

// The exponential and logarithm go through the 4x4 generator [[sigma I + hat(phi), rho], [0, 0]];
// Eigen's matrix functions are exact to rounding and need no small-angle special cases.
Sim3 Sim3::exp(const Vector7d& xi) {
  Eigen::Matrix4d A = Eigen::Matrix4d::Zero();
  A.topLeftCorner<3, 3>() = xi(6) * Eigen::Matrix3d::Identity() + hat(xi.segment<3>(3));
  A.topRightCorner<3, 1>() = xi.head<3>();
  const Eigen::Matrix4d M = A.exp();
  const double s = std::exp(xi(6));
  return Sim3(s, Eigen::Quaterniond(so3_exp(xi.segment<3>(3))), M.topRightCorner<3, 1>());
}

Vector7d Sim3::log() const {
  const Eigen::Matrix4d L = matrix().log();
  Vector7d xi;
  xi.head<3>() = L.topRightCorner<3, 1>();
  xi.segment<3>(3) = so3_log(q_.toRotationMatrix());
  xi(6) = std::log(s_);
  return xi;
}

Sim3 Sim3::inverse() const {
  const Eigen::Quaterniond qi = q_.conjugate();
  return Sim3(1.0 / s_, qi, -(qi * t_) / s_);
}

Sim3 Sim3::operator*(const Sim3& o) const { return Sim3(s_ * o.s_, q_ * o.q_, s_ * (q_ * o.t_) + t_); }

Eigen::Matrix4d Sim3::matrix() const {
  Eigen::Matrix4d T = Eigen::Matrix4d::Identity();
  T.topLeftCorner<3, 3>() = s_ * q_.toRotationMatrix();
  T.topRightCorner<3, 1>() = t_;
  return T;
}

}  // namespace wardmap::slam
