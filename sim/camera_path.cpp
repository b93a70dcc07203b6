#include "sim/camera_path.h"

#include <algorithm>
#include <cmath>

#include "sim/rng.h"

namespace wardmap::sim {

namespace {
constexpr double kDeg = M_PI / 180.0;
constexpr double kShakeHz = 4.5;  // blur challenge: shake frequency
double wrap_pi(double a) {
  while (a > M_PI) a -= 2 * M_PI;
  while (a <= -M_PI) a += 2 * M_PI;
  return a;
}
}  // namespace

Eigen::Matrix3d camera_rotation(double yaw, double pitch, double roll) {
  Eigen::Matrix3d R0;  // columns: camera x (right), y (down), z (forward) for yaw = pitch = roll = 0
  R0.col(0) = Eigen::Vector3d(0, -1, 0);
  R0.col(1) = Eigen::Vector3d(0, 0, -1);
  R0.col(2) = Eigen::Vector3d(1, 0, 0);
  return (Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()) * Eigen::AngleAxisd(-pitch, Eigen::Vector3d::UnitY()) *
          Eigen::AngleAxisd(roll, Eigen::Vector3d::UnitX()))
             .toRotationMatrix() *
         R0;
}

MonotoneSpline::MonotoneSpline(std::vector<double> t, std::vector<double> y)
    : t_(std::move(t)), y_(std::move(y)), m_(t_.size(), 0.0) {
  const size_t n = t_.size();
  // PCHIP (Fritsch-Butland) interior slopes: weighted harmonic mean of the neighbouring secants.
  for (size_t k = 1; k + 1 < n; ++k) {
    const double h0 = t_[k] - t_[k - 1], h1 = t_[k + 1] - t_[k];
    const double d0 = (y_[k] - y_[k - 1]) / h0, d1 = (y_[k + 1] - y_[k]) / h1;
    if (d0 * d1 <= 0) continue;
    const double w1 = 2 * h1 + h0, w2 = h1 + 2 * h0;
    m_[k] = (w1 + w2) / (w1 / d0 + w2 / d1);
  }
}

double MonotoneSpline::operator()(double t) const {
  if (t <= t_.front()) return y_.front();
  if (t >= t_.back()) return y_.back();
  const size_t k = static_cast<size_t>(std::upper_bound(t_.begin(), t_.end(), t) - t_.begin()) - 1;
  const double h = t_[k + 1] - t_[k], s = (t - t_[k]) / h;
  const double s2 = s * s, s3 = s2 * s;
  return (2 * s3 - 3 * s2 + 1) * y_[k] + (s3 - 2 * s2 + s) * h * m_[k] + (-2 * s3 + 3 * s2) * y_[k + 1] +
         (s3 - s2) * h * m_[k + 1];
}

CameraPath::CameraPath(const Scenario& s, Variant variant, uint32_t seed) : platform_(s.platform) {
  const size_t n = s.waypoints.size();
  std::vector<double> px(n), py(n), pz(n), yaw(n), pitch(n), roll(n);
  for (size_t i = 0; i < n; ++i) {
    const WaypointSpec& w = s.waypoints[i];
    px[i] = w.position.x();
    py[i] = w.position.y();
    pz[i] = w.position.z();
    if (w.has_look_at) {
      const Eigen::Vector3d d = w.look_at - w.position;
      yaw[i] = std::atan2(d.y(), d.x());
      pitch[i] = std::atan2(d.z(), d.head<2>().norm());
    } else {
      yaw[i] = w.yaw_deg * kDeg;
      pitch[i] = w.pitch_deg * kDeg;
    }
    roll[i] = w.roll_deg * kDeg;
    if (i > 0) yaw[i] = yaw[i - 1] + wrap_pi(yaw[i] - yaw[i - 1]);  // shortest turn
  }
  const double factor = variant == Variant::kQuick ? s.quick_factor : 1.0;
  times_.assign(n, 0.0);
  for (size_t i = 1; i < n; ++i) {
    double d = s.waypoints[i].duration;
    if (d <= 0) {
      const double dist = (s.waypoints[i].position - s.waypoints[i - 1].position).norm();
      const double turn = std::max(std::abs(yaw[i] - yaw[i - 1]), std::abs(pitch[i] - pitch[i - 1]));
      d = std::max({dist / s.speed, turn / (s.turn_rate_deg * kDeg), 0.2});
    }
    times_[i] = times_[i - 1] + d * factor;
  }
  x_ = MonotoneSpline(times_, px);
  y_ = MonotoneSpline(times_, py);
  z_ = MonotoneSpline(times_, pz);
  yaw_ = MonotoneSpline(times_, yaw);
  pitch_ = MonotoneSpline(times_, pitch);
  roll_ = MonotoneSpline(times_, roll);
  Rng rng = Rng::derived(seed, 0x70a7u);
  for (double& p : phase_) p = rng.uniform(0, 2 * M_PI);
}

slam::SE3 CameraPath::pose(double t) const {
  t = std::clamp(t, 0.0, duration());
  Eigen::Vector3d p(x_(t), y_(t), z_(t));
  double yaw = yaw_(t), pitch = pitch_(t), roll = roll_(t);
  const double w = 2 * M_PI * t;
  if (platform_ == Platform::kRobot) {  // wheels on tiles: small fast vibration
    pitch += 0.3 * kDeg * std::sin(2.1 * w + phase_[0]);
    roll += 0.2 * kDeg * std::sin(1.3 * w + phase_[1]);
    p.z() += 0.003 * std::sin(2.9 * w + phase_[2]);
  } else {  // hovering: slow sway
    roll += 2.5 * kDeg * std::sin(0.35 * w + phase_[0]);
    pitch += 1.5 * kDeg * std::sin(0.27 * w + phase_[1]);
    yaw += 1.0 * kDeg * std::sin(0.2 * w + phase_[3]);
    p.z() += 0.04 * std::sin(0.3 * w + phase_[2]);
    p.y() += 0.03 * std::sin(0.23 * w + phase_[4]);
  }
  for (const ShakeWindow& s : shakes_) {
    if (t <= s.t_begin || t >= s.t_end) continue;
    // circular shake (constant angular speed, so every frame is smeared), eased in and out
    const double ramp = std::min(0.3, 0.25 * (s.t_end - s.t_begin));
    double e = std::clamp(std::min(t - s.t_begin, s.t_end - t) / ramp, 0.0, 1.0);
    e = e * e * (3 - 2 * e);
    const double a = 2 * M_PI * kShakeHz * t + phase_[5];
    yaw += s.amplitude * e * std::sin(a);
    pitch += 0.7 * s.amplitude * e * std::cos(a);
  }
  return slam::SE3(camera_rotation(yaw, pitch, roll), p);
}

}  // namespace wardmap::sim
