// A timed sequence of camera-to-world poses (the ground truth of a sequence or an estimate).
#pragma once

#include <vector>

#include "slam/core/se3.h"

namespace wardmap::slam {

struct Trajectory {
  std::vector<double> timestamps;  // seconds, strictly increasing
  std::vector<SE3> poses;          // camera-to-world
  // KITTI pose files carry no time: then `indexed` is true and timestamps hold frame indices.
  bool indexed = false;

  size_t size() const { return poses.size(); }
  bool empty() const { return poses.empty(); }
  void push_back(double t, const SE3& T) {
    timestamps.push_back(t);
    poses.push_back(T);
  }
  // The poses with t0 <= timestamp <= t1 (`indexed` kept).
  Trajectory within(double t0, double t1) const {
    Trajectory out;
    out.indexed = indexed;
    for (size_t k = 0; k < size(); ++k)
      if (timestamps[k] >= t0 && timestamps[k] <= t1) out.push_back(timestamps[k], poses[k]);
    return out;
  }
};

}  // namespace wardmap::slam
