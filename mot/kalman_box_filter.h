// Constant-velocity Kalman filter on an image box (Assoc. III-A.1, the motion model of FairMOT/DeepSORT).
// State x = [cx, cy, a, h, vcx, vcy, va, vh] with a = w / h; measurement z = [cx, cy, a, h].
// Noise standard deviations scale with the box height, so the filter behaves the same at any image scale.
#pragma once

#include <Eigen/Core>
#include <optional>
#include <string>

namespace wardmap::mot {

using Vector4d = Eigen::Matrix<double, 4, 1>;
using Vector8d = Eigen::Matrix<double, 8, 1>;
using Matrix4d = Eigen::Matrix<double, 4, 4>;
using Matrix8d = Eigen::Matrix<double, 8, 8>;

// Box corners (x0, y0, x1, y1) <-> measurement (cx, cy, w / h, h).
Vector4d corners_to_xyah(const Vector4d& corners);
Vector4d xyah_to_corners(const Vector4d& xyah);

// Chi-square quantiles for gating on the squared Mahalanobis distance (4 dof = full box, 2 dof = centre).
inline constexpr double kChi2Inv95Dof4 = 9.4877;
inline constexpr double kChi2Inv95Dof2 = 5.9915;

struct KalmanBoxOptions {
  double std_weight_position = 1.0 / 20;   // DeepSORT / FairMOT: position noise = h / 20
  double std_weight_velocity = 1.0 / 160;  // velocity noise = h / 160 (per frame)
  double std_aspect = 1e-2;                // aspect-ratio measurement noise
  double std_aspect_velocity = 1e-5;       // aspect-ratio velocity process noise
  // Empty when valid, else a sentence naming the offending field.
  std::optional<std::string> validate() const;
};

struct BoxState {
  Vector8d mean = Vector8d::Zero();
  Matrix8d covariance = Matrix8d::Identity();
  // The box the state predicts, as corners.
  Vector4d corners() const { return xyah_to_corners(mean.head<4>()); }
};

class KalmanBoxFilter {
 public:
  explicit KalmanBoxFilter(const KalmanBoxOptions& options = {});

  // A new state at measurement z with zero velocity and a wide velocity prior.
  BoxState initiate(const Vector4d& xyah) const;
  // Propagate by dt frames (dt may be fractional or > 1 when keyframes are unevenly spaced).
  void predict(BoxState& state, double dt = 1.0) const;
  // Measurement-space mean and covariance (H x, H P H^T + R).
  void project(const BoxState& state, Vector4d* mean, Matrix4d* covariance) const;
  // Standard Kalman correction with measurement z.
  void update(BoxState& state, const Vector4d& xyah) const;
  // Squared Mahalanobis distance of z to the projected state; on (cx, cy) only when position_only.
  double gating_distance(const BoxState& state, const Vector4d& xyah, bool position_only = false) const;

  const KalmanBoxOptions& options() const { return options_; }

 private:
  Vector4d measurement_std(double h) const;
  KalmanBoxOptions options_;
};

}  // namespace wardmap::mot
