// Camera paths: waypoints with orientation, interpolated in time by monotone cubic Hermite splines
// (PCHIP, per channel: position x/y/z, yaw, pitch, roll; at rest at both ends, no overshoot), plus
// the platform's own motion (a robot's small vibration, a drone's sway) and the shake of blur
// challenges. Poses are camera-to-world in the OpenCV camera frame (x right, y down, z forward) in
// the z-up world frame of sim/scenario.h.
#pragma once

#include <vector>

#include "sim/scenario.h"
#include "slam/core/se3.h"

namespace wardmap::sim {

enum class Variant { kSlow, kQuick };

// Camera-to-world rotation looking along yaw/pitch (radians; yaw from +x towards +y, pitch up),
// rolled about the optical axis.
Eigen::Matrix3d camera_rotation(double yaw, double pitch, double roll);

// One channel of a monotone cubic Hermite spline through (t[i], y[i]), zero slope at the ends.
class MonotoneSpline {
 public:
  MonotoneSpline() = default;
  MonotoneSpline(std::vector<double> t, std::vector<double> y);
  double operator()(double t) const;

 private:
  std::vector<double> t_, y_, m_;
};

struct ShakeWindow {
  double t_begin, t_end;
  double amplitude;  // radians of yaw (pitch gets 0.7 of it), circling at 4.5 Hz
};

class CameraPath {
 public:
  CameraPath(const Scenario& scenario, Variant variant, uint32_t seed);

  double duration() const { return times_.back(); }
  double waypoint_time(int i) const { return times_.at(static_cast<size_t>(i)); }
  // Shakes added on top of the path (blur challenges).
  void add_shake(const ShakeWindow& w) { shakes_.push_back(w); }
  // Camera-to-world pose at t seconds from the start (clamped to [0, duration()]).
  slam::SE3 pose(double t) const;

 private:
  std::vector<double> times_;
  MonotoneSpline x_, y_, z_, yaw_, pitch_, roll_;
  Platform platform_;
  double phase_[6] = {};
  std::vector<ShakeWindow> shakes_;
};

}  // namespace wardmap::sim
