// When the tracker inserts a keyframe (ORB-SLAM's NeedNewKeyFrame for RGB-D): often enough, when
// the frame tracks clearly fewer points than its reference keyframe holds, or when too few close
// points are tracked while many close keypoints are unmatched; and always after keyframe_max_frames.
// Unlike ORB-SLAM, a camera whose view has not moved since the last keyframe (keyframe_still_px)
// makes none unless tracking is weak: a robot waiting at a door would make one every few frames.
// A busy mapper takes one only when tracking is weak or deferring it would leave too long a gap.
// The mapper counts as busy for mapping.min_busy_seconds after each keyframe, idle or not.
#pragma once

#include <limits>

#include "slam/front/front_options.h"

namespace wardmap::slam {

struct KeyFrameEvidence {
  int frames_since_keyframe = 0;
  int tracked_inliers = 0;   // frame's matched inliers after local-map tracking
  int reference_points = 0;  // reference keyframe's points with enough observations
  int keyframes_in_map = 0;
  int tracked_close = 0;    // close keypoints with a matched point
  int untracked_close = 0;  // close keypoints without one
  bool mapper_idle = true;
  // The last keyframe is younger than mapping.min_busy_seconds (sequence time): the mapper counts
  // as busy even if it is idle, as a mapper taking its usual time per keyframe would be.
  bool keyframe_too_recent = false;
  bool mapper_queue_full = false;  // then no keyframe: the queue must not grow without bound
  bool mapper_keyframes_waiting = false;  // keyframes queued, not yet taken by the mapper
  // Seconds from the last keyframe to the next frame (this frame's period ahead): the gap a keyframe
  // deferred to the next frame would leave.
  double deferred_gap_seconds = 0;
  // Median image motion (px) of the frame's tracked points between the last keyframe's pose and
  // this frame's: how far the view has moved since the last keyframe (infinite when not measured).
  double view_motion_px = std::numeric_limits<double>::infinity();
};

bool need_new_keyframe(const KeyFrameEvidence& e, const TrackingOptions& options);

}  // namespace wardmap::slam
