// Local bundle adjustment (Ceres, Schur elimination of the points) around a keyframe: the keyframe
// and its best covisible neighbours are optimised together with every point they see; the other
// keyframes observing those points are held fixed. A robust pass (Huber) is followed by a chi2 test
// and a refinement without outliers; the outlier observations are then removed from the map.
#pragma once

#include <functional>
#include <memory>
#include <mutex>

#include "slam/core/camera.h"
#include "slam/front/front_options.h"
#include "slam/front/key_frame.h"

namespace wardmap::slam {

class Submap;

struct LocalBAResult {
  int keyframes = 0;  // optimised
  int fixed_keyframes = 0;
  int points = 0;
  int observations = 0;
  int outliers = 0;  // observations removed
  double initial_cost = 0, final_cost = 0;
  bool aborted = false;  // `abort` cut the solve short
};

// `lock`, when given, holds the submap's mutex: it is released while Ceres solves (the problem works on
// copies of the poses and positions) and taken again to write the results back. `abort`, when given,
// is asked after every solver iteration: true ends the solve there and skips the refinement (ORB-SLAM's
// local BA stops when a new keyframe arrives); what was reached is kept.
LocalBAResult local_bundle_adjustment(const std::shared_ptr<KeyFrame>& keyframe, Submap& submap,
                                      const PinholeCamera& camera, const FrontOptions& options,
                                      std::unique_lock<std::mutex>* lock = nullptr,
                                      const std::function<bool()>& abort = {});

}  // namespace wardmap::slam
