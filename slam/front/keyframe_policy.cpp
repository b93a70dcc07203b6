#include "slam/front/keyframe_policy.h"

namespace wardmap::slam {

bool need_new_keyframe(const KeyFrameEvidence& e, const TrackingOptions& o) {
  if (e.mapper_queue_full) return false;
  const double ref_ratio = e.keyframes_in_map < 2 ? 0.4 : o.keyframe_ref_ratio;
  const bool need_close = e.tracked_close < o.keyframe_close_tracked && e.untracked_close > o.keyframe_close_untracked;
  const bool too_long = e.frames_since_keyframe >= o.keyframe_max_frames;
  const bool accepts = (e.mapper_idle && !e.keyframe_too_recent) ||
                       (!e.mapper_keyframes_waiting && e.deferred_gap_seconds > o.keyframe_max_gap_seconds);
  const bool weak = e.tracked_inliers < 0.25 * e.reference_points || need_close;
  const bool fewer_than_reference =
      (e.tracked_inliers < ref_ratio * e.reference_points || need_close) && e.tracked_inliers > 15;
  // A view unmoved since the last keyframe adds nothing to the map: a keyframe only if tracking is
  // about to fail (a scene changing in front of a still camera).
  if (e.view_motion_px < o.keyframe_still_px) return e.tracked_inliers > 15 && e.tracked_inliers < 0.25 * e.reference_points;
  // Unlike ORB-SLAM, a keyframe is also due after keyframe_max_frames whatever the reference holds
  // (its reference count is 0 until points gain observations, which a sparse map may never reach).
  if (too_long && e.tracked_inliers > 15) return true;
  return (accepts || weak) && fewer_than_reference;
}

}  // namespace wardmap::slam
