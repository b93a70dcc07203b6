#include "slam/front/tracker.h"

#include <algorithm>
#include <cmath>
#include <opencv2/calib3d.hpp>
#include <opencv2/core/eigen.hpp>
#include <opencv2/video/tracking.hpp>
#include <unordered_set>

#include "slam/front/descriptor_distance.h"
#include "slam/front/keyframe_policy.h"
#include "slam/front/local_bundle_adjustment.h"
#include "slam/front/local_map.h"
#include "slam/front/rgbd_points.h"
#include "slam/front/submap.h"
#include "slam/front/two_view.h"

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

namespace {

// The median distance between matched keypoints of two frames (pixels).
double median_displacement(const std::vector<Eigen::Vector2d>& p1, const std::vector<Eigen::Vector2d>& p2) {
  if (p1.empty()) return 0;
  std::vector<double> d(p1.size());
  for (size_t i = 0; i < p1.size(); ++i) d[i] = (p2[i] - p1[i]).norm();
  std::nth_element(d.begin(), d.begin() + static_cast<long>(d.size() / 2), d.end());
  return d[d.size() / 2];
}

}  // namespace

Tracker::Tracker(const FrontOptions& options, const PinholeCamera& camera, LocalMapper& mapper)
    : options_(options), camera_(camera), matcher_(options.matcher, camera), mapper_(mapper) {
  pose_options_.rounds = options.tracking.pose_rounds;
  pose_options_.iterations = options.tracking.pose_iterations;
  pose_options_.solver = options.tracking.pose_solver == "ceres" ? PoseSolver::kCeres : PoseSolver::kLevenbergMarquardt;
  pose_options_.chi2_mono = options.tracking.chi2_mono;
  pose_options_.chi2_stereo = options.tracking.chi2_stereo;
  if (options_.monocular) {
    options_.tracking.motion_radius = options_.tracking.motion_radius_mono;
    options_.tracking.keyframe_ref_ratio = options_.tracking.keyframe_ref_ratio_mono;
    options_.tracking.keyframe_ref_min_observations = options_.tracking.keyframe_ref_min_observations_mono;
  }
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
  init_reference_.reset();
  place_database_.clear();
  unindexed_.clear();
}

TrackingOutcome Tracker::track(Frame& frame) {
  TrackingOutcome out;
  if (state_ == TrackingState::kNotInitialised) {
    if (initialise(frame)) {
      state_ = TrackingState::kTracking;
      out.tracked = out.keyframe = true;
      out.inliers = frame.count_matches();
      out.backfilled = std::move(backfilled_);
      backfilled_.clear();
    }
    out.state = state_;
    out.reference = reference_;
    if (out.tracked) last_frame_ = std::make_unique<Frame>(frame);
    return out;
  }

  index_new_keyframes(false);
  bool ok = false;
  if (state_ == TrackingState::kTracking) {
    replace_fused_points(*last_frame_);
    ok = velocity_ && track_with_motion_model(frame);
    if (!ok) ok = track_reference_keyframe(frame);
  } else if (vocabulary_) {
    ok = out.relocalised = relocalise(frame);
  } else {
    // Lost without a vocabulary: the latest keyframe from the last known pose.
    frame.set_pose_cw(last_frame_->pose_cw());
    ok = track_reference_keyframe(frame) && plausible_recovery(frame);
  }
  out.matches = frame.count_matches();
  if (ok) {
    frame.reference_keyframe = reference_;
    ok = track_local_map(frame, out.inliers);
    if (ok && options_.tracking.flow(options_.monocular)) {
      const int gained = extend_by_flow(frame);
      if (options_.tracking.flow_counts_for_keyframes) out.inliers += gained;
    }
  }
  out.relocalised = out.relocalised && ok;
  state_ = ok ? TrackingState::kTracking : TrackingState::kLost;
  frames_lost_ = ok ? 0 : frames_lost_ + 1;
  out.state = state_;
  out.tracked = ok;
  if (ok) {
    velocity_ = frame.pose_cw() * last_frame_->pose_cw().inverse();
    KeyFrameEvidence ev = evidence(frame, out.inliers);
    if (wants_keyframe(frame, ev)) {
      insert_keyframe(frame);
      out.keyframe = true;
    } else if (!ev.mapper_idle && mapper_.threaded()) {
      KeyFrameEvidence if_idle = ev;
      if_idle.mapper_idle = true;
      if (wants_keyframe(frame, if_idle)) mapper_.interrupt_ba();  // a keyframe next frame
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
  return options_.monocular ? initialise_monocular(frame) : initialise_rgbd(frame);
}

bool Tracker::initialise_monocular(Frame& frame) {
  const TrackingOptions& t = options_.tracking;
  if (static_cast<int>(frame.size()) <= t.init_min_features) {
    init_reference_.reset();
    return false;
  }
  const bool aged = init_reference_ && frame.id() - init_since_ > static_cast<std::uint64_t>(t.init_max_frames);
  if (aged && t.init_still_px > 0 && !init_window_moved_ && !init_window_.empty()) {
    // Every frame since the reference shows its view unmoved: the camera stands still, and a newer
    // reference would be no better. Keep it; its frames take its pose once the map exists.
    for (const Frame& f : init_window_) init_still_.push_back(f.timestamp());
    init_since_ = init_window_.back().id();
    init_window_.clear();
  } else if (!init_reference_ || aged) {
    init_reference_ = std::make_unique<Frame>(frame);
    init_prior_ = frame.features().points;
    init_since_ = frame.id();
    init_window_.clear();
    init_window_moved_ = false;
    init_still_.clear();
    return false;
  }
  const FrameFeatures& f1 = init_reference_->features();
  std::vector<Eigen::Vector2d> prior = init_prior_;
  std::vector<int> m12 =
      matcher_.search_for_initialisation(f1, frame.features(), init_prior_, t.init_window, t.init_ratio);
  if (t.init_level_span > 0 &&
      std::count_if(m12.begin(), m12.end(), [](int j) { return j >= 0; }) < t.init_min_matches) {
    // Few keypoints kept their level: the camera may be closing in (or backing off) fast, so each
    // corner is now found a level up (down). Search the neighbouring levels from the same priors.
    init_prior_ = std::move(prior);
    m12 = matcher_.search_for_initialisation(f1, frame.features(), init_prior_, t.init_window, t.init_ratio,
                                             t.init_level_span);
  }
  std::vector<Eigen::Vector2d> p1, p2;
  std::vector<int> index1;
  for (size_t i = 0; i < m12.size(); ++i) {
    if (m12[i] < 0) continue;
    p1.push_back(f1.points[i]);
    p2.push_back(frame.features().points[static_cast<size_t>(m12[i])]);
    index1.push_back(static_cast<int>(i));
  }
  if (static_cast<int>(p1.size()) < t.init_min_matches) {
    init_reference_.reset();  // too few matches: the next frame becomes the reference
    return false;
  }
  TwoViewOptions tv = t.two_view;
  tv.seed = init_reference_->id() * 1000003u + frame.id();
  const auto r = reconstruct_two_views(p1, p2, camera_, tv);
  if (!r) {  // not enough parallax or ambiguous: keep the reference, try the next frame
    init_window_.push_back(frame);
    init_window_moved_ = init_window_moved_ || median_displacement(p1, p2) >= t.init_still_px;
    return false;
  }
  // Matches re-indexed on the reference frame's keypoints, keeping only the triangulated ones.
  std::vector<int> matches(f1.size(), -1);
  TwoViewReconstruction rr = *r;
  std::vector<Eigen::Vector3d> points(f1.size());
  for (size_t k = 0; k < index1.size(); ++k) {
    if (!r->triangulated[k]) continue;
    matches[static_cast<size_t>(index1[k])] = m12[static_cast<size_t>(index1[k])];
    points[static_cast<size_t>(index1[k])] = r->points[k];
  }
  rr.points = std::move(points);
  const bool ok = create_initial_map(*init_reference_, frame, matches, rr);
  if (ok) {
    const auto kfs = submap_->recent_keyframes(2);  // newest first
    backfilled_ = backfill_initialisation_window(kfs[1], kfs[0]);
  }
  init_reference_.reset();
  init_window_.clear();
  init_still_.clear();
  return ok;
}

std::vector<TrackingOutcome::Backfilled> Tracker::backfill_initialisation_window(const std::shared_ptr<KeyFrame>& k1,
                                                                                const std::shared_ptr<KeyFrame>& k2) {
  const KeyFrame &kf1 = *k1, &kf2 = *k2;
  std::vector<TrackingOutcome::Backfilled> out{{kf1.timestamp(), kf1.pose_cw(), k1}};
  for (double still : init_still_) out.push_back({still, kf1.pose_cw(), k1});  // the view of the first keyframe
  std::vector<std::shared_ptr<MapPoint>> points;
  for (const auto& [id, mp] : submap_->map_points())
    if (!mp->bad()) points.push_back(mp);
  // The camera left the first keyframe's view after its last still frame.
  const double left = init_still_.empty() ? kf1.timestamp() : init_still_.back();
  const double span = kf2.timestamp() - left;
  for (Frame& f : init_window_) {
    // Start from the pose interpolated between the two keyframes, then track against the new map.
    const double s = span > 0 ? (f.timestamp() - left) / span : 0.5;
    f.set_pose_cw(SE3::interpolate(kf1.pose_cw(), kf2.pose_cw(), s));
    std::fill(f.map_points.begin(), f.map_points.end(), nullptr);
    std::fill(f.outlier.begin(), f.outlier.end(), 0);
    const auto candidates = visible_candidates(f, points, camera_);
    matcher_.search_by_projection(f, candidates, 2 * options_.tracking.local_map_radius);
    int inliers = optimise_frame_pose(f);
    if (inliers < options_.tracking.min_local_map_inliers) continue;
    // A second pass from the refined pose catches the points the interpolated pose missed.
    std::fill(f.map_points.begin(), f.map_points.end(), nullptr);
    std::fill(f.outlier.begin(), f.outlier.end(), 0);
    matcher_.search_by_projection(f, visible_candidates(f, points, camera_), options_.tracking.local_map_radius);
    inliers = optimise_frame_pose(f);
    if (inliers < options_.tracking.min_local_map_inliers) continue;
    for (size_t i = 0; i < f.size(); ++i)
      if (f.map_points[i] && !f.outlier[i]) f.map_points[i]->increase_found();
    out.push_back({f.timestamp(), f.pose_cw(), s < 0.5 ? k1 : k2});
  }
  return out;
}

bool Tracker::create_initial_map(Frame& first, Frame& second, const std::vector<int>& matches12,
                                 const TwoViewReconstruction& r) {
  first.set_pose_cw(initial_pose_cw_);
  second.set_pose_cw(r.T_21 * initial_pose_cw_);
  auto kf1 = submap_->create_keyframe(first);
  auto kf2 = submap_->create_keyframe(second);
  const SE3 T_w1 = initial_pose_cw_.inverse();
  for (size_t i = 0; i < matches12.size(); ++i) {
    if (matches12[i] < 0) continue;
    auto mp = submap_->create_map_point(T_w1 * r.points[i], *kf1);
    mp->add_observation(kf1, static_cast<int>(i));
    mp->add_observation(kf2, matches12[i]);
    kf1->set_map_point(i, mp);
    kf2->set_map_point(static_cast<size_t>(matches12[i]), mp);
    mp->update_descriptor();
    mp->update_normal_and_depth();
  }
  kf1->update_connections();
  kf2->update_connections();
  local_bundle_adjustment(kf2, *submap_, camera_, options_);  // the first keyframe holds the gauge
  // Scale: the median depth of the first keyframe's points becomes 1 (ORB-SLAM's convention).
  std::vector<double> depths;
  for (const auto& mp : kf1->map_points())
    if (mp && !mp->bad()) depths.push_back((kf1->pose_cw() * mp->position()).z());
  if (depths.empty()) {
    submap_->clear();
    return false;
  }
  std::nth_element(depths.begin(), depths.begin() + static_cast<long>(depths.size() / 2), depths.end());
  const double median = depths[depths.size() / 2];
  if (median <= 0 || kf2->tracked_points(1) < options_.tracking.two_view.min_triangulated) {
    submap_->clear();
    return false;
  }
  const double s = 1.0 / median;
  const SE3 T21 = kf2->pose_cw() * kf1->pose_wc();
  kf2->set_pose_cw(SE3(T21.rotation(), s * T21.translation()) * kf1->pose_cw());
  for (const auto& mp : kf1->map_points())
    if (mp && !mp->bad()) mp->set_position(kf1->pose_wc() * (s * (kf1->pose_cw() * mp->position())));
  for (const auto& mp : kf2->map_points())
    if (mp && !mp->bad()) mp->update_normal_and_depth();

  second.set_pose_cw(kf2->pose_cw());
  std::fill(second.map_points.begin(), second.map_points.end(), nullptr);
  std::fill(second.outlier.begin(), second.outlier.end(), 0);
  for (size_t i = 0; i < kf2->size(); ++i)
    if (kf2->map_point(i) && !kf2->map_point(i)->bad()) second.map_points[i] = kf2->map_point(i);
  if (vocabulary_) {  // the mapper registers kf1 before kf2; its triangulation with kf2 needs kf2's words
    kf1->compute_words(*vocabulary_);
    kf2->compute_words(*vocabulary_);
  }
  unindexed_.push_back(kf1);
  adopt_keyframe(second, kf2);
  mapper_.enqueue(kf1);
  mapper_.enqueue(kf2);
  mapper_.process_queued();
  return true;
}

bool Tracker::initialise_rgbd(Frame& frame) {
  int with_depth = 0;
  for (size_t i = 0; i < frame.size(); ++i) with_depth += frame.features().has_depth(i) ? 1 : 0;
  if (with_depth < options_.tracking.min_init_points) return false;
  frame.set_pose_cw(initial_pose_cw_);
  auto kf = submap_->create_keyframe(frame);
  auto created = create_depth_points(kf, *submap_, camera_, options_.tracking, /*every_depth=*/true);
  for (const auto& [i, mp] : created) frame.map_points[static_cast<size_t>(i)] = mp;
  adopt_keyframe(frame, kf);
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

void Tracker::replace_fused_points(Frame& frame) {
  // ORB-SLAM's CheckReplacedInLastFrame: the mapper fuses duplicate points; the frame keeps the
  // survivor instead of a point that is gone.
  for (auto& mp : frame.map_points)
    for (int hops = 0; mp && mp->bad() && hops < 8; ++hops) mp = mp->replaced_by();
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

int Tracker::extend_by_flow(Frame& frame) {
  const TrackingOptions& t = options_.tracking;
  if (!last_frame_ || last_frame_->flow_pyramid.empty() || frame.flow_pyramid.empty()) return 0;
  std::unordered_set<const MapPoint*> matched;
  for (size_t i = 0; i < frame.size(); ++i)
    if (frame.map_points[i] && !frame.outlier[i]) matched.insert(frame.map_points[i].get());
  const FrameFeatures& lf = last_frame_->features();
  std::vector<cv::Point2f> from, to;
  std::vector<size_t> source;
  std::vector<Eigen::Vector2d> predicted;
  for (size_t i = 0; i < last_frame_->size(); ++i) {
    const auto& mp = last_frame_->map_points[i];
    if (!mp || mp->bad() || !mp->descriptor() || last_frame_->outlier[i] || matched.count(mp.get())) continue;
    if (i >= lf.detected() && lf.flow_age[i - lf.detected()] >= t.flow_max_age) continue;
    const Eigen::Vector3d pc = frame.pose_cw() * mp->position();
    if (pc.z() <= 0) continue;
    const Eigen::Vector2d u = camera_.project(pc);
    if (!camera_.in_image(u, 2)) continue;
    const cv::Point2f p0 = lf.keypoints[i].pt;
    // The guess: the last keypoint moved by its point's predicted motion (undistorted offsets).
    const Eigen::Vector2d d = u - lf.points[i];
    from.push_back(p0);
    to.emplace_back(p0.x + static_cast<float>(d.x()), p0.y + static_cast<float>(d.y()));
    source.push_back(i);
    predicted.push_back(u);
  }
  if (from.empty()) return 0;
  if (from.size() > static_cast<size_t>(t.flow_max_points)) {  // the most observed points first
    std::vector<size_t> order(from.size());
    for (size_t k = 0; k < order.size(); ++k) order[k] = k;
    std::vector<int> obs(from.size());
    for (size_t k = 0; k < obs.size(); ++k) obs[k] = last_frame_->map_points[source[k]]->num_observations();
    std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) { return obs[a] > obs[b]; });
    order.resize(static_cast<size_t>(t.flow_max_points));
    std::sort(order.begin(), order.end());
    for (size_t n = 0; n < order.size(); ++n) {
      from[n] = from[order[n]];
      to[n] = to[order[n]];
      source[n] = source[order[n]];
      predicted[n] = predicted[order[n]];
    }
    from.resize(order.size());
    to.resize(order.size());
    source.resize(order.size());
    predicted.resize(order.size());
  }
  const cv::Size window(t.flow_window, t.flow_window);
  const cv::TermCriteria stop(cv::TermCriteria::COUNT | cv::TermCriteria::EPS, 30, 0.01);
  std::vector<uchar> ok1, ok2;
  std::vector<float> err;
  cv::calcOpticalFlowPyrLK(last_frame_->flow_pyramid, frame.flow_pyramid, from, to, ok1, err, window, t.flow_levels, stop,
                           cv::OPTFLOW_USE_INITIAL_FLOW);
  std::vector<cv::Point2f> back = from;
  cv::calcOpticalFlowPyrLK(frame.flow_pyramid, last_frame_->flow_pyramid, to, back, ok2, err, window, t.flow_levels, stop,
                           cv::OPTFLOW_USE_INITIAL_FLOW);
  std::shared_ptr<FrameFeatures> f;  // the frame's features, copied when the first keypoint is appended
  const size_t first = frame.size();
  // Each followed point lands on a slot: a detected keypoint within flow_snap pixels (unmatched:
  // it takes the point; matched to another point: a duplicate, dropped) or a keypoint appended here.
  std::vector<std::pair<size_t, std::shared_ptr<MapPoint>>> assigned;
  std::vector<char> taken(first, 0);
  std::vector<int> near;
  size_t appended = 0;
  for (size_t k = 0; k < from.size(); ++k) {
    if (!ok1[k] || !ok2[k] || cv::norm(back[k] - from[k]) > t.flow_max_fb_error) continue;
    const Eigen::Vector2d px(to[k].x, to[k].y);
    if (!camera_.in_image(px, 2)) continue;
    const Eigen::Vector2d und = camera_.has_distortion() ? camera_.undistort_point(px) : px;
    if ((und - predicted[k]).norm() > t.flow_gate) continue;
    const size_t i = source[k];
    const std::shared_ptr<MapPoint>& mp = last_frame_->map_points[i];
    if (t.flow_snap > 0) {
      frame.features().grid.in_area(und.x(), und.y(), t.flow_snap, std::max(0, lf.levels[i] - 1), lf.levels[i] + 1,
                                    near);
      bool duplicate = false;
      int best = -1;
      double best_d = t.flow_snap * t.flow_snap;
      for (int j : near) {
        const auto uj = static_cast<size_t>(j);
        const double dj = (frame.features().points[uj] - und).squaredNorm();
        if (dj > t.flow_snap * t.flow_snap) continue;
        if ((frame.map_points[uj] && !frame.outlier[uj]) || taken[uj]) {
          duplicate = true;
          break;
        }
        if (dj <= best_d) best_d = dj, best = j;
      }
      if (duplicate) continue;
      if (best >= 0) {
        taken[static_cast<size_t>(best)] = 1;
        frame.outlier[static_cast<size_t>(best)] = 0;
        assigned.emplace_back(static_cast<size_t>(best), mp);
        continue;
      }
    }
    if (!f) {
      f = std::make_shared<FrameFeatures>(frame.features());
      f->descriptors = f->descriptors.clone();  // shared with the frame's features until now
    }
    cv::KeyPoint kp = lf.keypoints[i];
    kp.pt = to[k];
    f->keypoints.push_back(kp);
    f->points.push_back(und);
    f->levels.push_back(lf.levels[i]);
    const float d = frame.depth.empty() || !t.flow_depth ? 0.f
                                        : sample_keypoint_depth(frame.depth, to[k], f->pyramid->scale[static_cast<size_t>(kp.octave)],
                                                                t.max_depth, t.max_depth_step);
    f->depth.push_back(d);
    f->right_u.push_back(d > 0 ? static_cast<float>(und.x() - f->bf / d) : -1.f);
    f->descriptors.push_back(cv::Mat(1, kDescriptorBytes, CV_8U, const_cast<uchar*>(mp->descriptor())));  // copies
    f->flow_age.push_back(i >= lf.detected() ? lf.flow_age[i - lf.detected()] + 1 : 1);
    assigned.emplace_back(first + appended++, mp);
  }
  if (assigned.empty()) return 0;
  if (f) {
    f->grid = FeatureGrid(f->points, f->levels, camera_.width, camera_.height);
    frame.extend_features(std::move(f));
  }
  for (const auto& [slot, mp] : assigned) frame.map_points[slot] = mp;
  if (t.flow_reoptimise) {
    optimise_frame_pose(frame);
  } else {  // the pose stays; each followed point passes the pose solver's chi2 test at it
    const FrameFeatures& ff = frame.features();
    for (const auto& [slot, mp] : assigned) {
      const PoseObservation o{mp->position(), ff.points[slot], ff.right_u[slot],
                              ff.pyramid->inv_scale[static_cast<size_t>(ff.levels[slot])]};
      const double th = o.right_u >= 0 ? t.chi2_stereo : t.chi2_mono;
      frame.outlier[slot] = observation_chi2(frame.pose_cw(), o, camera_, ff.bf) <= th ? 0 : 1;
    }
  }
  int gained = 0;
  for (const auto& [slot, mp] : assigned) {
    if (frame.outlier[slot]) continue;
    mp->increase_visible();
    mp->increase_found();
    mp->set_last_seen(frame.timestamp());
    if (mp->num_observations() > 0) ++gained;
  }
  return gained;
}

double Tracker::view_motion_px(const Frame& frame, const KeyFrame& keyframe) const {
  std::vector<Eigen::Vector2d> in_keyframe, in_frame;
  const SE3& T_kw = keyframe.pose_cw();
  for (size_t i = 0; i < frame.size(); ++i) {
    const auto& mp = frame.map_points[i];
    if (!mp || frame.outlier[i]) continue;
    const Eigen::Vector3d p_k = T_kw * mp->position(), p_f = frame.pose_cw() * mp->position();
    if (p_k.z() <= 0 || p_f.z() <= 0) continue;
    in_keyframe.push_back(camera_.project(p_k));
    in_frame.push_back(camera_.project(p_f));
  }
  if (in_frame.empty()) return std::numeric_limits<double>::infinity();
  return median_displacement(in_keyframe, in_frame);
}

bool Tracker::wants_keyframe(const Frame& frame, KeyFrameEvidence& e) const {
  const bool if_moved = need_new_keyframe(e, options_.tracking);
  KeyFrameEvidence unmoved = e;
  unmoved.view_motion_px = 0;
  if (if_moved == need_new_keyframe(unmoved, options_.tracking) || !last_keyframe_) return if_moved;
  if (std::isinf(e.view_motion_px)) e.view_motion_px = view_motion_px(frame, *last_keyframe_);
  return need_new_keyframe(e, options_.tracking);
}

KeyFrameEvidence Tracker::evidence(const Frame& frame, int inliers) const {
  KeyFrameEvidence e;
  e.frames_since_keyframe = static_cast<int>(frame.id() - last_keyframe_frame_);
  e.tracked_inliers = inliers;
  e.keyframes_in_map = static_cast<int>(submap_->num_keyframes());
  const int min_obs_setting = options_.tracking.keyframe_ref_min_observations;
  const int min_obs = e.keyframes_in_map <= 2 ? std::min(2, min_obs_setting) : min_obs_setting;
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
  e.keyframe_too_recent = frame.timestamp() - last_keyframe_time_ < options_.mapping.min_busy_seconds;
  e.mapper_queue_full = mapper_.queue_full();
  e.mapper_keyframes_waiting = mapper_.queued() > 0;
  const double period = last_frame_ ? frame.timestamp() - last_frame_->timestamp() : 0.0;
  e.deferred_gap_seconds = frame.timestamp() - last_keyframe_time_ + period;
  return e;
}

void Tracker::insert_keyframe(Frame& frame) {
  auto kf = submap_->create_keyframe(frame);
  std::vector<std::pair<int, std::shared_ptr<MapPoint>>> created;
  if (!options_.monocular) created = create_depth_points(kf, *submap_, camera_, options_.tracking);
  for (const auto& [i, mp] : created) {
    frame.map_points[static_cast<size_t>(i)] = mp;
    frame.outlier[static_cast<size_t>(i)] = 0;
  }
  adopt_keyframe(frame, kf);
  if (!mapper_.enqueue(kf)) return;  // mapper saturated: the keyframe still serves as reference
  mapper_.process_queued();          // inline mapping in this milestone
}

void Tracker::adopt_keyframe(Frame& frame, const std::shared_ptr<KeyFrame>& kf) {
  unindexed_.push_back(kf);
  reference_ = last_keyframe_ = kf;
  last_keyframe_frame_ = frame.id();
  last_keyframe_time_ = frame.timestamp();
  frame.reference_keyframe = kf;
}

void Tracker::index_new_keyframes(bool compute_missing) {
  for (const KeyFrameId id : submap_->take_culled()) place_database_.erase(id);
  size_t waiting = 0;
  for (auto& kf : unindexed_) {
    if (!vocabulary_ || kf->bad()) continue;
    if (compute_missing) kf->compute_words(*vocabulary_);
    if (!kf->bow.empty()) place_database_.add(kf->id(), kf->bow);
    else if (!compute_missing) unindexed_[waiting++] = kf;  // the mapper has not registered it yet
  }
  unindexed_.resize(waiting);
}

bool Tracker::plausible_recovery(const Frame& frame) const {
  // With metric depth, a place farther than the camera can have moved since it was last tracked is
  // a look-alike (repeated doors and walls), not the camera's place.
  if (options_.monocular || !last_frame_) return true;
  const double dt = frame.timestamp() - last_frame_->timestamp();
  const double moved = (frame.camera_center() - last_frame_->camera_center()).norm();
  return moved <= options_.tracking.reloc_max_speed * dt + options_.tracking.reloc_distance_margin;
}

bool Tracker::relocalise(Frame& frame) {
  const TrackingOptions& t = options_.tracking;
  index_new_keyframes(true);
  if (place_database_.size() == 0 || frame.size() == 0) return false;
  const place::BowVector bow = vocabulary_->transform(frame.features().descriptors);
  const auto candidates = place_database_.query(bow, static_cast<size_t>(t.reloc_candidates));
  const FrameFeatures& f = frame.features();
  cv::Mat K = (cv::Mat_<double>(3, 3) << camera_.fx, 0, camera_.cx, 0, camera_.fy, camera_.cy, 0, 0, 1);
  for (const auto& c : candidates) {
    const auto it = submap_->keyframes().find(c.id);
    if (it == submap_->keyframes().end() || it->second->bad()) continue;  // culled since
    const std::shared_ptr<KeyFrame>& kf = it->second;
    std::fill(frame.map_points.begin(), frame.map_points.end(), nullptr);
    std::fill(frame.outlier.begin(), frame.outlier.end(), 0);
    if (matcher_.search_by_knn(*kf, frame) < t.reloc_min_matches) continue;
    std::vector<cv::Point3d> object;
    std::vector<cv::Point2d> image;
    std::vector<size_t> slot;
    for (size_t i = 0; i < frame.size(); ++i) {
      const auto& mp = frame.map_points[i];
      if (!mp || mp->bad()) continue;
      object.emplace_back(mp->position().x(), mp->position().y(), mp->position().z());
      image.emplace_back(f.points[i].x(), f.points[i].y());
      slot.push_back(i);
    }
    if (static_cast<int>(object.size()) < t.reloc_min_matches) continue;
    cv::Mat rvec, tvec;
    std::vector<int> inliers;
    if (!cv::solvePnPRansac(object, image, K, cv::noArray(), rvec, tvec, false, 300,
                            static_cast<float>(t.reloc_pnp_error), 0.99, inliers, cv::SOLVEPNP_EPNP) ||
        inliers.size() < 10)
      continue;
    std::vector<char> keep(slot.size(), 0);
    for (int k : inliers) keep[static_cast<size_t>(k)] = 1;
    for (size_t k = 0; k < slot.size(); ++k)
      if (!keep[k]) frame.map_points[slot[k]].reset();
    cv::Mat R;
    cv::Rodrigues(rvec, R);
    Eigen::Matrix3d Re;
    Eigen::Vector3d te;
    cv::cv2eigen(R, Re);
    cv::cv2eigen(tvec, te);
    frame.set_pose_cw(SE3(Re, te));
    int good = optimise_frame_pose(frame);
    frame.drop_outliers();
    if (good < t.reloc_min_inliers) {
      // More matches by projecting the candidate's points from the PnP pose.
      std::vector<std::shared_ptr<MapPoint>> points;
      for (const auto& mp : kf->map_points())
        if (mp && !mp->bad()) points.push_back(mp);
      for (const auto& mp : frame.map_points)
        if (mp) mp->track_frame_id = frame.id();
      matcher_.search_by_projection(frame, visible_candidates(frame, points, camera_), 10.0);
      good = optimise_frame_pose(frame);
      frame.drop_outliers();
    }
    if (good < t.reloc_min_inliers || !plausible_recovery(frame)) continue;
    reference_ = kf;
    return true;
  }
  std::fill(frame.map_points.begin(), frame.map_points.end(), nullptr);
  return false;
}

}  // namespace wardmap::slam
