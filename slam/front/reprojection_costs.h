// Ceres cost functors for ORB observations of 3-D points in a pinhole camera with undistorted pixel
// coordinates. Poses are world-to-camera, stored as an Eigen quaternion (x, y, z, w; use
// ceres::EigenQuaternionManifold) and a translation. Residuals are whitened by the keypoint's
// level sigma. The "stereo" variants add the virtual right-image coordinate u_r = u - bf / z that an
// RGB-D depth measurement gives (as in ORB-SLAM's RGB-D mode).
#pragma once

#include <ceres/ceres.h>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "slam/core/se3.h"
#include "slam/front/pose_optimizer.h"

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

// Bundle adjustment: pose and point, by automatic differentiation. Parameters: q (4), t (3), point (3).
// The local BA uses BundleReprojectionCost below; this is the reference its test checks it against.
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

// The bundle-adjustment residual of ReprojectionCost with hand-written Jacobians in the same
// ambient coordinates (q as Eigen stores it, x y z w; t; the point), so that the solver takes the same
// steps as with automatic differentiation, about four times cheaper. The pose is one block of 7
// (q then t; give it ProductManifold<EigenQuaternionManifold, EuclideanManifold<3>>): Ceres then
// eliminates the points into 6x6 camera blocks, not twice as many 3x3 ones. With q = (w, v), Eigen
// computes R p = p + 2 w (v x p) + 2 v x (v x p); its derivatives are
//   d/dw = 2 (v x p),  d/dv = -2 w [p]x + 2 ((v . p) I + v p^T - 2 p v^T).
// A test checks them against the automatic ones.
template <int kResiduals>
class BundleReprojectionCost : public ceres::SizedCostFunction<kResiduals, 7, 3> {
  static_assert(kResiduals == 2 || kResiduals == 3);

 public:
  BundleReprojectionCost(const PinholeIntrinsics& k, const Eigen::Vector2d& pixel, double right_u, double inv_sigma)
      : k_(k), pixel_(pixel), right_u_(right_u), inv_sigma_(inv_sigma) {}

  bool Evaluate(double const* const* parameters, double* residuals, double** jacobians) const override {
    const double* q = parameters[0];
    const Eigen::Map<const Eigen::Vector3d> v(q), t(q + 4), p(parameters[1]);
    const double w = q[3];
    const Eigen::Vector3d vxp = v.cross(p);
    const Eigen::Vector3d pc = p + 2.0 * w * vxp + 2.0 * v.cross(vxp) + t;
    const double iz = 1.0 / pc.z(), s = inv_sigma_;
    const double u = k_.fx * pc.x() * iz + k_.cx, vv = k_.fy * pc.y() * iz + k_.cy;
    residuals[0] = (u - pixel_.x()) * s;
    residuals[1] = (vv - pixel_.y()) * s;
    if constexpr (kResiduals == 3) residuals[2] = (u - k_.bf * iz - right_u_) * s;
    if (!jacobians) return true;
    // d(residual)/d(pc), whitened.
    Eigen::Matrix<double, kResiduals, 3> Jp;
    Jp.row(0) << k_.fx * iz, 0, -k_.fx * pc.x() * iz * iz;
    Jp.row(1) << 0, k_.fy * iz, -k_.fy * pc.y() * iz * iz;
    if constexpr (kResiduals == 3) Jp.row(2) << k_.fx * iz, 0, (-k_.fx * pc.x() + k_.bf) * iz * iz;
    Jp *= s;
    if (jacobians[0]) {
      Eigen::Matrix<double, 3, 4> Jq;
      const double vp = v.dot(p);
      Eigen::Matrix3d Jv = 2.0 * (vp * Eigen::Matrix3d::Identity() + v * p.transpose() - 2.0 * p * v.transpose());
      Jv += -2.0 * w * skew(p);
      Jq.leftCols<3>() = Jv;
      Jq.col(3) = 2.0 * vxp;
      Eigen::Map<Eigen::Matrix<double, kResiduals, 7, Eigen::RowMajor>> J_pose(jacobians[0]);
      J_pose.template leftCols<4>() = Jp * Jq;
      J_pose.template rightCols<3>() = Jp;
    }
    if (jacobians[1]) {
      // d(R p)/dp = R, with R written from the same (not necessarily unit) q as the formula above.
      const Eigen::Matrix3d V = skew(v);
      const Eigen::Matrix3d R = Eigen::Matrix3d::Identity() + 2.0 * w * V + 2.0 * V * V;
      Eigen::Map<Eigen::Matrix<double, kResiduals, 3, Eigen::RowMajor>> Jx_out(jacobians[1]);
      Jx_out = Jp * R;
    }
    return true;
  }

  static Eigen::Matrix3d skew(const Eigen::Vector3d& a) {
    Eigen::Matrix3d m;
    m << 0, -a.z(), a.y(), a.z(), 0, -a.x(), -a.y(), a.x(), 0;
    return m;
  }

 private:
  PinholeIntrinsics k_;
  Eigen::Vector2d pixel_;
  double right_u_;
  double inv_sigma_;
};

// Reprojection residual of a fixed point under T = exp(delta) * T0, delta = (rho, phi) a left
// perturbation, with the analytic Jacobian d(pc)/d(delta) = [I | -[pc]x] evaluated at the current
// point (exact at delta = 0; each round restarts from delta = 0). One residual block per
// observation: the textbook form of pose-only optimisation, which the tracker's solver
// (optimize_pose, all of a round's observations in one block) is tested against.
template <int kResiduals>
class PosePerturbationCost : public ceres::SizedCostFunction<kResiduals, 6> {
 public:
  PosePerturbationCost(const PinholeIntrinsics& k, const SE3& T0, const PoseObservation& o)
      : k_(k), p0_(T0 * o.point), o_(o) {}

  bool Evaluate(double const* const* parameters, double* residuals, double** jacobians) const override {
    Vector6d delta;
    for (int i = 0; i < 6; ++i) delta[i] = parameters[0][i];
    const Eigen::Vector3d pc = SE3::exp(delta) * p0_;
    if (pc.z() <= 1e-9) return false;
    const double iz = 1.0 / pc.z(), s = o_.inv_sigma;
    const double u = k_.fx * pc.x() * iz + k_.cx, v = k_.fy * pc.y() * iz + k_.cy;
    residuals[0] = (u - o_.pixel.x()) * s;
    residuals[1] = (v - o_.pixel.y()) * s;
    if constexpr (kResiduals == 3) residuals[2] = (u - k_.bf * iz - o_.right_u) * s;
    if (jacobians && jacobians[0]) {
      Eigen::Matrix<double, kResiduals, 3> Jp;
      Jp.row(0) << k_.fx * iz, 0, -k_.fx * pc.x() * iz * iz;
      Jp.row(1) << 0, k_.fy * iz, -k_.fy * pc.y() * iz * iz;
      if constexpr (kResiduals == 3) Jp.row(2) << k_.fx * iz, 0, (-k_.fx * pc.x() + k_.bf) * iz * iz;
      Eigen::Matrix<double, 3, 6> Jd;
      Jd.leftCols<3>().setIdentity();
      Jd.rightCols<3>() << 0, pc.z(), -pc.y(), -pc.z(), 0, pc.x(), pc.y(), -pc.x(), 0;
      Eigen::Map<Eigen::Matrix<double, kResiduals, 6, Eigen::RowMajor>> J(jacobians[0]);
      J = s * Jp * Jd;
    }
    return true;
  }

 private:
  PinholeIntrinsics k_;
  Eigen::Vector3d p0_;  // the point in the camera at T0
  PoseObservation o_;
};

}  // namespace wardmap::slam
