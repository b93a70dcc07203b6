// FairMOT-style multi-object tracker for the short-term association inside a keyframe group
// (Assoc. III-A.1). Each update is one (key)frame; the tracker returns, for every input detection,
// the id of the track it joined. Three matching stages, as in FairMOT's JDETracker:
//   1. confirmed + lost tracks (and, by default, tentative ones) vs detections: appearance cosine
//      distance fused with the Kalman motion gate,
//      cost = lambda * d_emb + (1 - lambda) * d_mahalanobis^2, the gate rejects; Hungarian;
//   2. the still unmatched *tracked* tracks vs the rest: IoU distance; Hungarian; unmatched -> lost;
//   3. the still unmatched tentative tracks vs the rest: IoU distance; Hungarian; unmatched -> dropped.
// Only same-class pairs are ever matched. Unmatched detections with a high enough score start
// tentative tracks; lost tracks not seen for max_lost_frames updates are dropped.
#pragma once

#include <Eigen/Core>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "mot/kalman_box_filter.h"

namespace wardmap::mot {

struct Detection {
  Eigen::Vector4d box = Eigen::Vector4d::Zero();  // x0, y0, x1, y1 (pixels, x1 > x0, y1 > y0)
  int class_id = 0;
  float score = 1.0f;
  Eigen::VectorXf embedding;  // L2-normalised appearance; empty = no appearance (stage 1 cannot match it)
  int user_index = -1;        // opaque, carried through for the caller
};

struct TrackerOptions {
  // FairMOT defaults (src/lib/tracker/multitracker.py), named after what they threshold.
  double min_score = 0.4;           // detections below are ignored (conf_thres)
  double new_track_score = 0.4;     // unmatched detections at or above start a track (det_thresh)
  double embedding_distance = 0.4;  // stage 1 assignment threshold on the fused cost
  double motion_lambda = 0.98;      // weight of appearance in the fused cost (fuse_motion lambda_)
  // Motion gate on the squared Mahalanobis distance between the predicted and detected box. FairMOT
  // gates all 4 measurement dims (cx, cy, a, h) at 9.4877 (chi2 95%, 4 dof) between video frames.
  // Keyframes are farther apart and detector aspect ratios jitter (the filter's aspect noise is
  // 1e-2), so the default gates the centre only (2 dof) at its 99.9% quantile. <= 0 disables the
  // gate (and the motion term of the fused cost).
  bool motion_gate_position_only = true;
  double motion_gate_chi2 = 13.816;
  double iou_distance_tracked = 0.5;      // stage 2 threshold on 1 - IoU
  double iou_distance_unconfirmed = 0.7;  // stage 3 threshold on 1 - IoU
  double duplicate_iou_distance = 0.15;   // a lost track this close to a tracked one is dropped
  double embedding_ema = 0.9;             // smoothed = ema * smoothed + (1 - ema) * new, renormalised
  // Deviation from FairMOT (which matches tentative tracks by IoU only, stage 3): tentative tracks
  // also take part in stage 1, so a new track survives keyframe-sized jumps when its appearance is
  // clear. false restores FairMOT.
  bool match_unconfirmed_by_appearance = true;
  int max_lost_frames = 30;            // track_buffer: updates a lost track survives
  int confirm_hits = 2;                // matches (incl. the first) before a track is confirmed
  bool confirm_in_first_frame = true;  // FairMOT activates every track born in the first frame
  KalmanBoxOptions kalman;
  // Empty when valid, else a sentence naming the offending field.
  std::optional<std::string> validate() const;
};

enum class TrackState { kTentative, kTracked, kLost };

struct Track {
  int id = -1;
  int class_id = 0;
  TrackState state = TrackState::kTentative;
  bool confirmed = false;
  BoxState kalman;
  Eigen::VectorXf embedding;  // smoothed, L2-normalised (empty until a detection carried one)
  int hits = 0;               // detections matched, including the one that started it
  int start_frame = 0, last_frame = 0;
  double score = 0;
  Eigen::Vector4d box() const { return kalman.corners(); }
};

// 1 - IoU of two corner boxes (1 when either is empty).
double iou_distance(const Eigen::Vector4d& a, const Eigen::Vector4d& b);

class Tracker {
 public:
  explicit Tracker(const TrackerOptions& options = {});

  // One frame. dt = elapsed frames since the previous update (1 for consecutive keyframes; may be
  // larger for a gap). Returns, per detection, the id of its track or -1 (score below min_score, or
  // unmatched and too weak to start a track). Tentative tracks' ids are returned too: they are
  // stable, and is_confirmed() tells them apart.
  std::vector<int> update(const std::vector<Detection>& detections, double dt = 1.0);

  // The same, with the camera's motion compensated: after the Kalman prediction, a track for which
  // `predicted_box` returns a box (corners) is moved there, with no image velocity left (what moves
  // a static object in the image is the camera, which the caller knows). Others keep the Kalman
  // prediction.
  using BoxPredictor = std::function<std::optional<Eigen::Vector4d>(const Track&)>;
  std::vector<int> update(const std::vector<Detection>& detections, double dt, const BoxPredictor& predicted_box);

  // Live tracks (tentative, tracked and lost), ordered by id.
  const std::vector<Track>& tracks() const { return tracks_; }
  const Track* find(int id) const;
  bool is_confirmed(int id) const;
  int frame_count() const { return frame_; }
  // Forget every track; ids keep increasing so they stay unique for this tracker's lifetime.
  void reset();

  const TrackerOptions& options() const { return options_; }

 private:
  void start_track(const Detection& d);
  void apply_match(Track& t, const Detection& d);

  TrackerOptions options_;
  KalmanBoxFilter kf_;
  std::vector<Track> tracks_;
  int next_id_ = 0;
  int frame_ = 0;
};

}  // namespace wardmap::mot
