// The part of a submap a frame is tracked against, sub_i of RUMI Formula 5: keyframes covisible with
// the frame's matches and their neighbours, plus the keyframes of the last Th_t seconds; of their
// points, those seen within Th_t (short-term association) or lying within Th_p of the camera
// (mid-term association). Then the points predicted in view of the frame (frustum, distance range,
// viewing angle), with their predicted pixel and pyramid level.
#pragma once

#include <memory>
#include <vector>

#include "slam/core/camera.h"
#include "slam/front/frame.h"
#include "slam/front/front_options.h"
#include "slam/front/orb_matcher.h"

namespace wardmap::slam {

class Submap;

struct LocalMap {
  std::vector<std::shared_ptr<KeyFrame>> keyframes;
  std::vector<std::shared_ptr<MapPoint>> points;
  std::shared_ptr<KeyFrame> reference;  // the keyframe sharing most points with the frame
};

// RUMI Formula 5: sub_i = {P : |t(p_q) - t(P)| < Th_t or |pos(p_q) - pos(P)| < Th_p}.
LocalMap build_local_map(const Frame& frame, const Submap& submap, const TrackingOptions& options);

// Local points not yet matched in `frame` that project inside it; each counts one more `visible`.
std::vector<ProjectionCandidate> visible_candidates(const Frame& frame,
                                                    const std::vector<std::shared_ptr<MapPoint>>& points,
                                                    const PinholeCamera& camera);

}  // namespace wardmap::slam
