#include "slam/front/front_process.h"

#include <opencv2/video/tracking.hpp>

#include <algorithm>
#include <chrono>
#include <optional>

namespace wardmap::slam {

double flow_budget_seconds(const TrackingOptions& t, bool monocular, const PinholeCamera& camera) {
  const double pixels = static_cast<double>(camera.width) * camera.height;
  return t.flow_budget_ms_for(monocular) / 1e3 * (pixels > 0 ? pixels / (640.0 * 480.0) : 1.0);
}

FrontProcess::FrontProcess(const FrontOptions& options, const PinholeCamera& camera)
    : options_(options),
      camera_(camera),
      extractor_(options.orb),
      init_extractor_([&options] {
        OrbOptions o = options.orb;
        o.n_features *= 2;
        return o;
      }()),
      ids_(std::make_shared<IdSource>()),
      submap_(std::make_shared<Submap>(0, ids_)),
      mapper_(options, camera),
      tracker_(options, camera, mapper_),
      // Timing decides the flow in threaded runs only: --deterministic output must not depend on it.
      flow_budget_(options.mapping_thread ? flow_budget_seconds(options.tracking, options.monocular, camera) : 0.0,
                   options.tracking.flow_budget_frames, options.tracking.flow_budget_retry) {
  options_.validate();
  submaps_.push_back(submap_);
  mapper_.set_submap(submap_);
  tracker_.set_submap(submap_);
  if (options_.mapping_thread) mapper_.start();
}

FrontProcess::~FrontProcess() { mapper_.stop(); }

void FrontProcess::finish() { mapper_.stop(); }

double FrontProcess::mapping_seconds_total() const { return mapper_.stats().total_seconds(); }

FrameResult FrontProcess::process(const io::Frame& in) {
  const auto start = std::chrono::steady_clock::now();
  const cv::Mat grey = to_grey(in.image);
  Frame frame(
      next_frame_id_++, in.timestamp,
      make_frame_features(
          grey, options_.monocular ? cv::Mat() : in.depth,
          options_.monocular && tracker_.state() == TrackingState::kNotInitialised ? init_extractor_ : extractor_,
          camera_, options_.tracking.virtual_baseline, options_.tracking.max_depth, options_.tracking.max_depth_step));
  const bool flow = options_.tracking.flow(options_.monocular) && flow_budget_.active();
  if (flow && options_.tracking.flow_depth && !options_.monocular && in.depth.type() == CV_32F) frame.depth = in.depth;
  if (flow)
    cv::buildOpticalFlowPyramid(grey, frame.flow_pyramid,
                                cv::Size(options_.tracking.flow_window, options_.tracking.flow_window),
                                options_.tracking.flow_levels);
  const auto extracted = std::chrono::steady_clock::now();
  const bool threaded = mapper_.threaded();
  double wait_seconds = 0;  // reported apart from the frame's own time (FrameResult::wait_seconds)
  // Waits until the mapper is idle, or for at most `budget` seconds when one is given.
  const auto wait_for_mapper = [this, &wait_seconds](std::optional<double> budget = std::nullopt) {
    const auto wait_start = std::chrono::steady_clock::now();
    if (budget) mapper_.wait_idle_for(*budget);
    else mapper_.wait_idle();
    wait_seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - wait_start).count();
  };
  // A live camera gives the mapper the sequence time between frames; offline input arrives faster.
  // The mapper gets that time here, counted from when the keyframe was made (it is never waited for
  // longer), so that the keyframes a threaded run makes do not depend on how fast frames are read.
  if (threaded && options_.mapping.sequence_time_for_mapper && keyframe_timestamp_ >= 0 && !mapper_.idle()) {
    const double budget = (in.timestamp - keyframe_timestamp_) -
                          std::chrono::duration<double>(std::chrono::steady_clock::now() - keyframe_clock_).count();
    if (budget > 0) wait_for_mapper(budget);
  }
  if (threaded && frames_since_keyframe_ >= options_.mapping.max_lag_frames && !mapper_.idle()) wait_for_mapper();
  ++frames_since_keyframe_;
  FrameResult r;
  bool start_submap = false;
  {
    // Threaded mapping: the tracker holds the submap for the whole frame (the mapper takes it step
    // by step). Inline: the mapper runs inside track() and its time is reported separately.
    std::unique_lock<std::mutex> lock;
    if (threaded) lock = std::unique_lock<std::mutex>(submap_->mutex());
    const double mapping_before = threaded ? 0 : mapping_seconds_total();
    const TrackingOutcome t = tracker_.track(frame);
    r.extract_seconds = std::chrono::duration<double>(extracted - start).count();
    r.mapping_seconds = threaded ? 0 : mapping_seconds_total() - mapping_before;
    r.index = in.index;
    r.timestamp = in.timestamp;
    r.state = t.state;
    r.tracked = t.tracked;
    r.keyframe = t.keyframe;
    r.relocalised = t.relocalised;
    if (t.keyframe) {
      frames_since_keyframe_ = 0;
      keyframe_clock_ = std::chrono::steady_clock::now();
      keyframe_timestamp_ = in.timestamp;
    }
    r.features = static_cast<int>(frame.size());
    r.matches = t.matches;
    r.inliers = t.inliers;
    r.submap = submap_->id();
    if (t.tracked) {
      r.T_wc = frame.pose_cw().inverse();
      last_tracked_pose_cw_ = frame.pose_cw();
      if (t.reference) {
        for (const auto& b : t.backfilled) {
          records_.push_back({b.timestamp, submap_->id(), b.reference, b.T_cw * b.reference->pose_wc()});
          r.backfilled.push_back(b.timestamp);
        }
        records_.push_back({in.timestamp, submap_->id(), t.reference, frame.pose_cw() * t.reference->pose_wc()});
      }
    } else if (t.state == TrackingState::kLost) {
      // A map this small is not worth relocalising into (ORB-SLAM resets it): start over.
      start_submap = tracker_.frames_lost() >= options_.tracking.lost_frames_to_reset ||
                     submap_->num_keyframes() <= static_cast<size_t>(options_.tracking.young_submap_keyframes);
    }
  }
  if (start_submap) {
    wait_for_mapper();  // the mapper finishes the old submap's keyframes first
    r.discarded_submap = submap_->num_keyframes() <= static_cast<size_t>(options_.tracking.discard_submap_keyframes);
    if (r.discarded_submap) {  // ORB-SLAM3 resets its active map: a fresh submap takes the id
      const int id = submap_->id();
      while (!records_.empty() && records_.back().submap == id) records_.pop_back();  // its frames are the newest
      submap_ = std::make_shared<Submap>(id, ids_);
      submaps_.back() = submap_;
    } else {
      submap_ = std::make_shared<Submap>(static_cast<int>(submaps_.size()), ids_);
      submaps_.push_back(submap_);
    }
    mapper_.set_submap(submap_);
    tracker_.set_submap(submap_, last_tracked_pose_cw_);
    flow_budget_.restart();  // the new map's first window has the flow, as the first map's had
    r.new_submap = true;
  }
  r.wait_seconds = wait_seconds;
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() - wait_seconds;
  r.flow = flow;
  // The budget weighs the frames the flow can run on: tracked ones (not initialisation or lost frames).
  if (options_.tracking.flow(options_.monocular) && r.tracked && r.state == TrackingState::kTracking)
    flow_budget_.record(r.seconds);
  return r;
}

SE3 resolved_pose_cw(const std::shared_ptr<KeyFrame>& kf) {
  SE3 T;  // accumulated T_{kf, current}
  std::shared_ptr<KeyFrame> k = kf;
  for (int guard = 0; k && k->bad() && guard < 10000; ++guard) {
    T = T * k->pose_relative_to_parent();
    k = k->parent();
  }
  return k ? T * k->pose_cw() : T;
}

Trajectory FrontProcess::trajectory() const {
  std::vector<size_t> frames(submaps_.size(), 0);
  for (const Record& r : records_) ++frames[static_cast<size_t>(r.submap)];
  const auto largest = std::max_element(frames.begin(), frames.end()) - frames.begin();
  return trajectory(static_cast<int>(largest));
}

Trajectory FrontProcess::trajectory(int submap_id) const {
  Trajectory traj;
  for (const Record& r : records_) {
    if (r.submap != submap_id) continue;
    const SE3 T_cw = r.T_cr * resolved_pose_cw(r.reference);
    if (!traj.timestamps.empty() && r.timestamp <= traj.timestamps.back()) continue;
    traj.push_back(r.timestamp, T_cw.inverse());
  }
  return traj;
}

}  // namespace wardmap::slam
