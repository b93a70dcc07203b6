// The realtime front-process as one object: feed it frames, get each frame's status and pose, and the
// trajectory of the tracked frames at any time (poses are kept relative to their reference keyframe,
// so bundle-adjustment corrections reach them). The entry point for `wardmap run`.
// When tracking stays lost for tracking.lost_frames_to_reset frames (no relocalisation yet), or is lost
// in a submap of at most tracking.young_submap_keyframes keyframes, a new submap is started, seeded at
// the last tracked pose; the old submaps are kept for a later merge, except one of at most
// tracking.discard_submap_keyframes keyframes, which is discarded and whose id the new submap takes.
#pragma once

#include <chrono>

#include <memory>
#include <vector>

#include "slam/core/camera.h"
#include "slam/core/trajectory.h"
#include "slam/front/flow_budget.h"
#include "slam/front/front_options.h"
#include "slam/front/local_mapper.h"
#include "slam/front/orb_extractor.h"
#include "slam/front/submap.h"
#include "slam/front/tracker.h"
#include "slam/io/sequence.h"

namespace wardmap::slam {

struct FrameResult {
  size_t index = 0;
  double timestamp = 0;
  TrackingState state = TrackingState::kNotInitialised;
  bool tracked = false;
  bool keyframe = false;
  bool relocalised = false;  // found again by place recognition after being lost
  SE3 T_wc;  // camera-to-world at the time of tracking (meaningful when tracked)
  int features = 0;
  int matches = 0;
  int inliers = 0;
  int submap = 0;              // id of the submap the frame was tracked in
  bool new_submap = false;     // tracking was lost too long: a new submap starts with the next frame
  // With new_submap: submap `submap` held too few keyframes to keep and is discarded. The frames
  // localised in it are lost now (gone from trajectory()), and the new submap takes its id.
  bool discarded_submap = false;
  // Monocular initialisation: timestamps of the earlier frames localised once the map existed, ascending.
  std::vector<double> backfilled;
  double seconds = 0;          // wall time spent on this frame (extraction, tracking, inline mapping)
  // Not in `seconds`: time waiting for a threaded mapper still busy mapping.max_lag_frames after a
  // keyframe (or finishing the old submap's keyframes when a new one starts). A camera delivering
  // frames in real time would not wait when the mapper keeps up with it.
  double wait_seconds = 0;
  double extract_seconds = 0;  // of which ORB extraction
  double mapping_seconds = 0;  // of which local mapping run inline (keyframes only; 0 when threaded)
  // The optical flow was on for this frame (tracking.flow_extend / _mono, within flow_budget_ms): its
  // pyramid was built, and points were followed if the frame was tracked.
  bool flow = false;
};

class FrontProcess {
 public:
  FrontProcess(const FrontOptions& options, const PinholeCamera& camera);
  ~FrontProcess();
  FrontProcess(const FrontProcess&) = delete;
  FrontProcess& operator=(const FrontProcess&) = delete;

  // Enables relocalisation by place recognition (call before the first frame).
  void set_vocabulary(std::shared_ptr<const place::Vocabulary> vocabulary) { tracker_.set_vocabulary(std::move(vocabulary)); }
  // Tracks one frame (grey or BGR image, CV_32F depth in metres).
  FrameResult process(const io::Frame& frame);
  // Ends the run: with options.mapping_thread, maps the queued keyframes and stops the mapper. Call it
  // before reading the trajectory, submaps or mapper statistics of a threaded run.
  void finish();
  // Camera-to-world poses of the frames tracked in the submap holding most frames (the whole run
  // when it never lost track), with the current keyframe poses.
  Trajectory trajectory() const;
  // The same for one submap.
  Trajectory trajectory(int submap_id) const;
  // The active submap, and every submap built so far (oldest first).
  const Submap& submap() const { return *submap_; }
  const std::vector<std::shared_ptr<Submap>>& submaps() const { return submaps_; }
  const LocalMapperStats& mapper_stats() const { return mapper_.stats(); }
  size_t mapper_queue_length() const { return mapper_.queued(); }
  TrackingState state() const { return tracker_.state(); }
  const place::KeyframeDatabase& place_database() const { return tracker_.place_database(); }

 private:
  struct Record {
    double timestamp;
    int submap;
    std::shared_ptr<KeyFrame> reference;
    SE3 T_cr;  // frame pose relative to its reference keyframe
  };

  FrontOptions options_;
  PinholeCamera camera_;
  OrbExtractor extractor_;
  OrbExtractor init_extractor_;  // monocular initialisation: twice the features (ORB-SLAM's choice)
  std::shared_ptr<IdSource> ids_;
  std::shared_ptr<Submap> submap_;
  std::vector<std::shared_ptr<Submap>> submaps_;
  LocalMapper mapper_;
  Tracker tracker_;
  FlowBudget flow_budget_;  // when the flow is on: whether it runs on the next frame
  double mapping_seconds_total() const;

  std::vector<Record> records_;
  std::uint64_t next_frame_id_ = 0;
  int frames_since_keyframe_ = 0;
  // When the last keyframe went to the mapper: wall clock and the frame's timestamp.
  std::chrono::steady_clock::time_point keyframe_clock_;
  double keyframe_timestamp_ = -1;
  SE3 last_tracked_pose_cw_;
};

// The flow's time budget for a frame of this camera: tracking.flow_budget_ms(_mono), given for 640 x 480,
// scaled by the image's pixel count (the targets: 10 ms monocular at 640 x 480, 15 ms on KITTI's
// 1241 x 376, 1.5 times the pixels).
double flow_budget_seconds(const TrackingOptions& tracking, bool monocular, const PinholeCamera& camera);

// Pose of keyframe kf (world-to-camera), following the parents of culled keyframes.
SE3 resolved_pose_cw(const std::shared_ptr<KeyFrame>& kf);

}  // namespace wardmap::slam
