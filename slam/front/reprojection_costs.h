// Ceres cost functors for ORB observations of 3-D points in a pinhole camera with undistorted pixel
// coordinates. Poses are world-to-camera, stored as an Eigen quaternion (x, y, z, w; use
// ceres::EigenQuaternionManifold) and a translation. Residuals are whitened by the keypoint's
// level sigma. The "stereo" variants add the virtual right-image coordinate u_r = u - bf / z that an
// RGB-D depth measurement gives (as in ORB-SLAM's RGB-D mode).
#pragma once

#include <ceres/ceres.h>

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace wardmap::slam {

struct PinholeIntrinsics {
  double fx, fy, cx, cy, bf;  // bf: virtual baseline x fx
};

template <typename T>
Eigen::Matrix<T, 3, 1> transform_point(const T* q, const T* t, const Eigen::Matrix<T, 3, 1>& p) {
  Eigen::Map<const Eigen::Quaternion<T>> Q(q);
  Eigen::Map<const Eigen::Matrix<T, 3, 1>> tt(t);
  return Q * p + tt;
}

// kStereo: 3 residuals (u, v, u_r); otherwise 2 (u, v).
template <bool kStereo>
struct ReprojectionResidual {
  ReprojectionResidual(const PinholeIntrinsics& k, const Eigen::Vector2d& pixel, double right_u, double inv_sigma)
      : k_(k), pixel_(pixel), right_u_(right_u), inv_sigma_(inv_sigma) {}
  template <typename T>
  bool residual(const Eigen::Matrix<T, 3, 1>& pc, T* r) const {
    const T inv_z = T(1) / pc.z();
    const T u = T(k_.fx) * pc.x() * inv_z + T(k_.cx);
    const T v = T(k_.fy) * pc.y() * inv_z + T(k_.cy);
    r[0] = (u - T(pixel_.x())) * T(inv_sigma_);
    r[1] = (v - T(pixel_.y())) * T(inv_sigma_);
    if constexpr (kStereo) r[2] = (u - T(k_.bf) * inv_z - T(right_u_)) * T(inv_sigma_);
    return true;
  }
  PinholeIntrinsics k_;
  Eigen::Vector2d pixel_;
  double right_u_;
  double inv_sigma_;
};

// Pose-only: the point is fixed. Parameters: q (4), t (3).
template <bool kStereo>
struct PoseReprojectionCost : ReprojectionResidual<kStereo> {
  static constexpr int kResiduals = kStereo ? 3 : 2;
  PoseReprojectionCost(const PinholeIntrinsics& k, const Eigen::Vector3d& point, const Eigen::Vector2d& pixel,
                       double right_u, double inv_sigma)
      : ReprojectionResidual<kStereo>(k, pixel, right_u, inv_sigma), point_(point) {}
  template <typename T>
  bool operator()(const T* q, const T* t, T* r) const {
    return this->residual(transform_point(q, t, Eigen::Matrix<T, 3, 1>(point_.cast<T>())), r);
  }
  static ceres::CostFunction* create(const PinholeIntrinsics& k, const Eigen::Vector3d& point,
                                     const Eigen::Vector2d& pixel, double right_u, double inv_sigma) {
    return new ceres::AutoDiffCostFunction<PoseReprojectionCost, kResiduals, 4, 3>(
        new PoseReprojectionCost(k, point, pixel, right_u, inv_sigma));
  }
  Eigen::Vector3d point_;
};

// Bundle adjustment: pose and point. Parameters: q (4), t (3), point (3).
template <bool kStereo>
struct ReprojectionCost : ReprojectionResidual<kStereo> {
  static constexpr int kResiduals = kStereo ? 3 : 2;
  using ReprojectionResidual<kStereo>::ReprojectionResidual;
  template <typename T>
  bool operator()(const T* q, const T* t, const T* p, T* r) const {
    return this->residual(transform_point(q, t, Eigen::Map<const Eigen::Matrix<T, 3, 1>>(p).eval()), r);
  }
  static ceres::CostFunction* create(const PinholeIntrinsics& k, const Eigen::Vector2d& pixel, double right_u,
                                     double inv_sigma) {
    return new ceres::AutoDiffCostFunction<ReprojectionCost, kResiduals, 4, 3, 3>(
        new ReprojectionCost(k, pixel, right_u, inv_sigma));
  }
};

}  // namespace wardmap::slam
