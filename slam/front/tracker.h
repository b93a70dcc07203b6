// Realtime tracking of one frame against the active submap: initialisation from the first frame's
// depth (RGB-D) or from two views (monocular, two_view.h), constant-velocity prediction + projection search of the last frame's points (fallback:
// brute-force matching against the reference keyframe), local-map tracking (RUMI Formula 5) with
// pose-only optimisation, and the keyframe decision. New keyframes go to the LocalMapper's queue.
#pragma once

#include <memory>
#include <optional>

#include "slam/core/camera.h"
#include "slam/front/frame.h"
#include "slam/front/front_options.h"
#include "slam/front/keyframe_policy.h"
#include "slam/front/local_mapper.h"
#include "slam/front/orb_matcher.h"
#include "slam/front/pose_optimizer.h"
#include "slam/place/keyframe_database.h"
#include "slam/place/vocabulary.h"

namespace wardmap::slam {

class Submap;

enum class TrackingState { kNotInitialised, kTracking, kLost };
const char* to_string(TrackingState s);

struct TrackingOutcome {
  TrackingState state = TrackingState::kNotInitialised;
  bool tracked = false;   // the frame has a pose in the submap
  bool keyframe = false;  // a keyframe was made from it
  bool relocalised = false;  // tracking was lost and found again by place recognition
  int matches = 0;        // after motion / reference tracking
  int inliers = 0;        // after local-map tracking
  std::shared_ptr<KeyFrame> reference;
  // Monocular initialisation: the earlier frames of the initialisation window (the reference frame,
  // the frames that showed its view unmoved, and those after), localised against the new map once it
  // exists; in time order.
  struct Backfilled {
    double timestamp;
    SE3 T_cw;
    std::shared_ptr<KeyFrame> reference;  // the initial keyframe nearer in time
  };
  std::vector<Backfilled> backfilled;
};

class Tracker {
 public:
  Tracker(const FrontOptions& options, const PinholeCamera& camera, LocalMapper& mapper);

  // Enables relocalisation by place recognition (bags of words of every keyframe from now on).
  void set_vocabulary(std::shared_ptr<const place::Vocabulary> vocabulary) {
    mapper_.set_vocabulary(vocabulary);
    vocabulary_ = std::move(vocabulary);
  }
  // Starts over on `submap`: the next frame with enough depth initialises it at `initial_pose_cw`.
  void set_submap(std::shared_ptr<Submap> submap, const SE3& initial_pose_cw = SE3());
  TrackingOutcome track(Frame& frame);
  TrackingState state() const { return state_; }
  // Consecutive frames lost since the last tracked one.
  int frames_lost() const { return frames_lost_; }
  // The keyframes relocalisation can find (those of the current submap, culled ones taken out).
  const place::KeyframeDatabase& place_database() const { return place_database_; }

 private:
  bool initialise(Frame& frame);
  bool initialise_rgbd(Frame& frame);
  bool initialise_monocular(Frame& frame);
  // Builds the first two keyframes and their points from a two-view reconstruction; false (and the
  // submap cleared) when bundle adjustment leaves too few points.
  bool create_initial_map(Frame& first, Frame& second, const std::vector<int>& matches12,
                          const struct TwoViewReconstruction& r);
  static void replace_fused_points(Frame& frame);
  bool track_with_motion_model(Frame& frame);
  bool track_reference_keyframe(Frame& frame);
  bool track_local_map(Frame& frame, int& inliers);
  // tracking.flow_extend (_mono): follows the last frame's map points that the frame did not match by
  // Lucas-Kanade flow, appends them as keypoints observing those points, re-optimises the pose.
  // Returns the inliers gained.
  int extend_by_flow(Frame& frame);
  // Lost: candidate keyframes of the submap by bag of words, descriptor matching, PnP RANSAC, pose
  // optimisation (ORB-SLAM's Relocalization). True with the frame's pose and matches set.
  bool relocalise(Frame& frame);
  // RGB-D: the recovered pose lies within reach of the last tracked one (reloc_max_speed x time +
  // reloc_distance_margin). Monocular maps have no metric scale: always true.
  bool plausible_recovery(const Frame& frame) const;
  int optimise_frame_pose(Frame& frame);  // returns inliers; flags outliers
  void insert_keyframe(Frame& frame);
  // Makes `kf`, created from `frame`, the reference and newest keyframe, and queues it for the
  // place database.
  void adopt_keyframe(Frame& frame, const std::shared_ptr<KeyFrame>& kf);
  // The evidence for need_new_keyframe, without the view's motion (view_motion_px below).
  KeyFrameEvidence evidence(const Frame& frame, int inliers) const;
  // need_new_keyframe on `e`, measuring the view's motion into it only when the answer depends on
  // it (tracking.keyframe_still_px): most frames skip those few hundred projections.
  bool wants_keyframe(const Frame& frame, KeyFrameEvidence& e) const;
  // Median pixel motion of the frame's tracked points between the keyframe's pose and the frame's
  // (tracking.keyframe_still_px); infinite without a tracked point in front of both.
  double view_motion_px(const Frame& frame, const KeyFrame& keyframe) const;

  FrontOptions options_;
  PinholeCamera camera_;
  OrbMatcher matcher_;
  PoseOptimizerOptions pose_options_;
  LocalMapper& mapper_;
  std::shared_ptr<Submap> submap_;
  TrackingState state_ = TrackingState::kNotInitialised;
  std::unique_ptr<Frame> last_frame_;
  std::optional<SE3> velocity_;  // T_{current, last}
  std::shared_ptr<KeyFrame> reference_;
  std::shared_ptr<KeyFrame> last_keyframe_;
  std::uint64_t last_keyframe_frame_ = 0;
  double last_keyframe_time_ = 0;  // its timestamp
  SE3 initial_pose_cw_;
  int frames_lost_ = 0;
  // Monocular initialisation: the first frame of the pair and where its keypoints were last matched.
  std::unique_ptr<Frame> init_reference_;
  std::vector<Eigen::Vector2d> init_prior_;
  std::vector<Frame> init_window_;  // the frames since init_reference_ (for backfilling)
  // tracking.init_still_px: the reference's age counts from this frame id; whether a frame of
  // init_window_ moved from the reference's view; the earlier frames that showed it unmoved.
  std::uint64_t init_since_ = 0;
  bool init_window_moved_ = false;
  std::vector<double> init_still_;
  std::vector<TrackingOutcome::Backfilled> backfilled_;
  std::shared_ptr<const place::Vocabulary> vocabulary_;
  place::KeyframeDatabase place_database_;
  std::vector<std::shared_ptr<KeyFrame>> unindexed_;  // keyframes not yet in place_database_
  // Takes the keyframes culled since the last call out of the place database, then adds the new
  // keyframes whose words the mapper has computed; with compute_missing (relocalisation needs them
  // all) computes the others' too.
  void index_new_keyframes(bool compute_missing);
  std::vector<TrackingOutcome::Backfilled> backfill_initialisation_window(const std::shared_ptr<KeyFrame>& kf1,
                                                                         const std::shared_ptr<KeyFrame>& kf2);
};

}  // namespace wardmap::slam
