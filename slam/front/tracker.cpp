#include "slam/front/tracker.h"

#include "slam/front/keyframe_policy.h"
#include "slam/front/local_map.h"
#include "slam/front/rgbd_points.h"
#include "slam/front/submap.h"

namespace wardmap::slam {

const char* to_string(TrackingState s) {
  switch (s) {
    case TrackingState::kNotInitialised:
      return "not-initialised";
    case TrackingState::kTracking:
      return "tracking";
    case TrackingState::kLost:
      return "lost";
  }
  return "?";
}

Tracker::Tracker(const FrontOptions& options, const PinholeCamera& camera, LocalMapper& mapper)
    : options_(options), camera_(camera), matcher_(options.matcher, camera), mapper_(mapper) {
  pose_options_.rounds = options.tracking.pose_rounds;
  pose_options_.iterations = options.tracking.pose_iterations;
  pose_options_.chi2_mono = options.tracking.chi2_mono;
  pose_options_.chi2_stereo = options.tracking.chi2_stereo;
}

void Tracker::set_submap(std::shared_ptr<Submap> submap, const SE3& initial_pose_cw) {
  submap_ = std::move(submap);
  initial_pose_cw_ = initial_pose_cw;
  frames_lost_ = 0;
  state_ = TrackingState::kNotInitialised;
  last_frame_.reset();
  velocity_.reset();
  reference_.reset();
  last_keyframe_.reset();
}

TrackingOutcome Tracker::track(Frame& frame) {
  TrackingOutcome out;
  if (state_ == TrackingState::kNotInitialised) {
    if (initialise(frame)) {
      state_ = TrackingState::kTracking;
      out.tracked = out.keyframe = true;
      out.inliers = frame.count_matches();
    }
    out.state = state_;
    out.reference = reference_;
    if (out.tracked) last_frame_ = std::make_unique<Frame>(frame);
    return out;
  }

  bool ok = false;
  if (state_ == TrackingState::kTracking) {
    ok = velocity_ && track_with_motion_model(frame);
    if (!ok) ok = track_reference_keyframe(frame);
  } else {
    // Lost: try the latest keyframe from the last known pose (no place recognition yet).
    frame.set_pose_cw(last_frame_->pose_cw());
    ok = track_reference_keyframe(frame);
  }
  out.matches = frame.count_matches();
  if (ok) {
    frame.reference_keyframe = reference_;
    ok = track_local_map(frame, out.inliers);
  }
  state_ = ok ? TrackingState::kTracking : TrackingState::kLost;
  frames_lost_ = ok ? 0 : frames_lost_ + 1;
  out.state = state_;
  out.tracked = ok;
  if (ok) {
    velocity_ = frame.pose_cw() * last_frame_->pose_cw().inverse();
    const KeyFrameEvidence ev = evidence(frame, out.inliers);
    if (need_new_keyframe(ev, options_.tracking)) {
      insert_keyframe(frame);
      out.keyframe = true;
    }
    frame.drop_outliers();
    last_frame_ = std::make_unique<Frame>(frame);
  } else {
    velocity_.reset();
  }
  out.reference = reference_;
  return out;
}

bool Tracker::initialise(Frame& frame) {
  int with_depth = 0;
  for (size_t i = 0; i < frame.size(); ++i) with_depth += frame.features().has_depth(i) ? 1 : 0;
  if (with_depth < options_.tracking.min_init_points) return false;
  frame.set_pose_cw(initial_pose_cw_);
  auto kf = submap_->create_keyframe(frame);
  auto created = create_depth_points(kf, *submap_, camera_, options_.tracking);
  for (const auto& [i, mp] : created) frame.map_points[static_cast<size_t>(i)] = mp;
  reference_ = last_keyframe_ = kf;
  last_keyframe_frame_ = frame.id();
  frame.reference_keyframe = kf;
  mapper_.enqueue(kf);
  mapper_.process_queued();
  return true;
}

int Tracker::optimise_frame_pose(Frame& frame) {
  const FrameFeatures& f = frame.features();
  std::vector<PoseObservation> obs;
  std::vector<size_t> slot;
  for (size_t i = 0; i < frame.size(); ++i) {
    const auto& mp = frame.map_points[i];
    if (!mp || mp->bad()) continue;
    obs.push_back({mp->position(), f.points[i], f.right_u[i], f.pyramid->inv_scale[static_cast<size_t>(f.levels[i])]});
    slot.push_back(i);
  }
  if (obs.size() < 3) return 0;
  const PoseEstimate est = optimize_pose(frame.pose_cw(), obs, camera_, f.bf, pose_options_);
  frame.set_pose_cw(est.T_cw);
  for (size_t k = 0; k < slot.size(); ++k) frame.outlier[slot[k]] = est.inlier[k] ? 0 : 1;
  return est.inliers;
}

bool Tracker::track_with_motion_model(Frame& frame) {
  frame.set_pose_cw(*velocity_ * last_frame_->pose_cw());
  const double r = options_.tracking.motion_radius;
  int n = matcher_.search_by_projection(frame, *last_frame_, r);
  if (n < options_.tracking.min_motion_matches) {
    std::fill(frame.map_points.begin(), frame.map_points.end(), nullptr);
    n = matcher_.search_by_projection(frame, *last_frame_, 2 * r);
  }
  if (n < options_.tracking.min_motion_matches) return false;
  const int inliers = optimise_frame_pose(frame);
  frame.drop_outliers();
  return inliers >= options_.tracking.min_pose_inliers;
}

bool Tracker::track_reference_keyframe(Frame& frame) {
  if (!reference_ || reference_->bad()) reference_ = last_keyframe_;
  if (!reference_ || reference_->bad()) return false;
  std::fill(frame.map_points.begin(), frame.map_points.end(), nullptr);
  const int n = matcher_.search_by_knn(*reference_, frame);
  if (n < 15) return false;
  frame.set_pose_cw(last_frame_->pose_cw());
  const int inliers = optimise_frame_pose(frame);
  frame.drop_outliers();
  return inliers >= options_.tracking.min_pose_inliers;
}

bool Tracker::track_local_map(Frame& frame, int& inliers) {
  for (const auto& mp : frame.map_points)
    if (mp && !mp->bad()) {
      mp->track_frame_id = frame.id();
      mp->increase_visible();
    }
  LocalMap local = build_local_map(frame, *submap_, options_.tracking);
  if (local.reference) reference_ = local.reference;
  const std::vector<ProjectionCandidate> candidates = visible_candidates(frame, local.points, camera_);
  matcher_.search_by_projection(frame, candidates, options_.tracking.local_map_radius);
  optimise_frame_pose(frame);
  inliers = 0;
  for (size_t i = 0; i < frame.size(); ++i) {
    const auto& mp = frame.map_points[i];
    if (!mp || mp->bad() || frame.outlier[i]) continue;
    mp->increase_found();
    mp->set_last_seen(frame.timestamp());
    if (mp->num_observations() > 0) ++inliers;
  }
  return inliers >= options_.tracking.min_local_map_inliers;
}

KeyFrameEvidence Tracker::evidence(const Frame& frame, int inliers) const {
  KeyFrameEvidence e;
  e.frames_since_keyframe = static_cast<int>(frame.id() - last_keyframe_frame_);
  e.tracked_inliers = inliers;
  e.keyframes_in_map = static_cast<int>(submap_->num_keyframes());
  const int min_obs = e.keyframes_in_map <= 2 ? 2 : 3;
  e.reference_points = reference_ ? reference_->tracked_points(min_obs) : 0;
  const FrameFeatures& f = frame.features();
  for (size_t i = 0; i < frame.size(); ++i) {
    if (f.depth[i] <= 0 || f.depth[i] > options_.tracking.close_depth) continue;
    if (frame.map_points[i] && !frame.outlier[i])
      ++e.tracked_close;
    else
      ++e.untracked_close;
  }
  e.mapper_idle = mapper_.idle();
  return e;
}

void Tracker::insert_keyframe(Frame& frame) {
  auto kf = submap_->create_keyframe(frame);
  auto created = create_depth_points(kf, *submap_, camera_, options_.tracking);
  for (const auto& [i, mp] : created) {
    frame.map_points[static_cast<size_t>(i)] = mp;
    frame.outlier[static_cast<size_t>(i)] = 0;
  }
  reference_ = last_keyframe_ = kf;
  last_keyframe_frame_ = frame.id();
  frame.reference_keyframe = kf;
  if (!mapper_.enqueue(kf)) return;  // mapper saturated: the keyframe still serves as reference
  mapper_.process_queued();          // inline mapping in this milestone
}

}  // namespace wardmap::slam
