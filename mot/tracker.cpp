#include "mot/tracker.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>

#include "mot/hungarian.h"

namespace wardmap::mot {
namespace {

constexpr double kForbidden = std::numeric_limits<double>::infinity();

bool valid_box(const Eigen::Vector4d& b) { return b.allFinite() && b(2) > b(0) && b(3) > b(1); }

// Cosine distance 1 - cos(a, b), clipped to >= 0 as in FairMOT; forbidden when either is missing.
double embedding_distance(const Eigen::VectorXf& a, const Eigen::VectorXf& b) {
  if (a.size() == 0 || b.size() == 0) return kForbidden;
  if (a.size() != b.size())
    throw std::invalid_argument("Tracker: embedding sizes differ (" + std::to_string(a.size()) + " vs " +
                                std::to_string(b.size()) + ")");
  const double na = a.norm(), nb = b.norm();
  if (!(na > 0) || !(nb > 0)) return kForbidden;
  return std::max(0.0, 1.0 - static_cast<double>(a.dot(b)) / (na * nb));
}

}  // namespace

double iou_distance(const Eigen::Vector4d& a, const Eigen::Vector4d& b) {
  const double iw = std::min(a(2), b(2)) - std::max(a(0), b(0));
  const double ih = std::min(a(3), b(3)) - std::max(a(1), b(1));
  const double area_a = (a(2) - a(0)) * (a(3) - a(1)), area_b = (b(2) - b(0)) * (b(3) - b(1));
  if (!(area_a > 0) || !(area_b > 0)) return 1.0;
  const double inter = (iw > 0 && ih > 0) ? iw * ih : 0.0;
  return 1.0 - inter / (area_a + area_b - inter);
}

std::optional<std::string> TrackerOptions::validate() const {
  std::ostringstream err;
  auto in_range = [&](const char* name, double v, double lo, double hi) {
    if (err.tellp() == 0 && !(v >= lo && v <= hi))
      err << name << " must lie in [" << lo << ", " << hi << "] (got " << v << ")";
  };
  in_range("min_score", min_score, 0, 1);
  in_range("new_track_score", new_track_score, 0, 1);
  in_range("embedding_distance", embedding_distance, 0, 2);
  in_range("motion_lambda", motion_lambda, 0, 1);
  in_range("iou_distance_tracked", iou_distance_tracked, 0, 1);
  in_range("iou_distance_unconfirmed", iou_distance_unconfirmed, 0, 1);
  in_range("duplicate_iou_distance", duplicate_iou_distance, 0, 1);
  in_range("embedding_ema", embedding_ema, 0, 1);
  if (err.tellp() == 0 && std::isnan(motion_gate_chi2))
    err << "motion_gate_chi2 must be a number (<= 0 disables the gate)";
  if (err.tellp() == 0 && max_lost_frames < 0) err << "max_lost_frames must be >= 0 (got " << max_lost_frames << ")";
  if (err.tellp() == 0 && confirm_hits < 1) err << "confirm_hits must be >= 1 (got " << confirm_hits << ")";
  if (err.tellp() == 0) {
    if (auto k = kalman.validate()) err << "kalman." << *k;
  }
  if (err.tellp() == 0) return std::nullopt;
  return err.str();
}

Tracker::Tracker(const TrackerOptions& options) : options_(options), kf_(options.kalman) {
  if (auto err = options_.validate()) throw std::invalid_argument("TrackerOptions: " + *err);
}

const Track* Tracker::find(int id) const {
  auto it = std::lower_bound(tracks_.begin(), tracks_.end(), id, [](const Track& t, int v) { return t.id < v; });
  return (it != tracks_.end() && it->id == id) ? &*it : nullptr;
}

bool Tracker::is_confirmed(int id) const {
  const Track* t = find(id);
  return t != nullptr && t->confirmed;
}

void Tracker::reset() {
  tracks_.clear();
  frame_ = 0;
}

void Tracker::start_track(const Detection& d) {
  Track t;
  t.id = next_id_++;
  t.class_id = d.class_id;
  t.kalman = kf_.initiate(corners_to_xyah(d.box));
  if (d.embedding.size() > 0 && d.embedding.norm() > 0) t.embedding = d.embedding.normalized();
  t.hits = 1;
  t.start_frame = t.last_frame = frame_;
  t.score = d.score;
  t.confirmed = t.hits >= options_.confirm_hits || (options_.confirm_in_first_frame && frame_ == 1);
  t.state = t.confirmed ? TrackState::kTracked : TrackState::kTentative;
  tracks_.push_back(std::move(t));
}

void Tracker::apply_match(Track& t, const Detection& d) {
  kf_.update(t.kalman, corners_to_xyah(d.box));
  if (d.embedding.size() > 0 && d.embedding.norm() > 0) {
    const Eigen::VectorXf e = d.embedding.normalized();
    if (t.embedding.size() == 0) {
      t.embedding = e;
    } else {
      if (t.embedding.size() != e.size()) throw std::invalid_argument("Tracker: embedding sizes differ");
      const float a = static_cast<float>(options_.embedding_ema);
      t.embedding = a * t.embedding + (1.0f - a) * e;
      if (t.embedding.norm() > 0) t.embedding.normalize();
    }
  }
  ++t.hits;
  t.last_frame = frame_;
  t.score = d.score;
  if (t.hits >= options_.confirm_hits) t.confirmed = true;
  t.state = t.confirmed ? TrackState::kTracked : TrackState::kTentative;
}

std::vector<int> Tracker::update(const std::vector<Detection>& detections, double dt) {
  return update(detections, dt, BoxPredictor());
}

std::vector<int> Tracker::update(const std::vector<Detection>& detections, double dt,
                                 const BoxPredictor& predicted_box) {
  ++frame_;
  for (Track& t : tracks_) {
    if (t.state != TrackState::kTracked) t.kalman.mean(7) = 0;  // FairMOT: no height velocity when not tracked
    kf_.predict(t.kalman, dt);
    if (!predicted_box) continue;
    if (const auto box = predicted_box(t); box && valid_box(*box)) {
      t.kalman.mean.head<4>() = corners_to_xyah(*box);
      t.kalman.mean.tail<4>().setZero();
    }
  }
  std::vector<int> result(detections.size(), -1);
  std::vector<int> open_dets;  // indices into detections still unmatched
  for (int i = 0; i < static_cast<int>(detections.size()); ++i)
    if (detections[i].score >= options_.min_score && valid_box(detections[i].box)) open_dets.push_back(i);

  std::vector<int> pool, unconfirmed;  // indices into tracks_
  for (int k = 0; k < static_cast<int>(tracks_.size()); ++k) (tracks_[k].confirmed ? pool : unconfirmed).push_back(k);
  if (options_.match_unconfirmed_by_appearance) pool.insert(pool.end(), unconfirmed.begin(), unconfirmed.end());

  // Runs one Hungarian stage of `rows` (tracks) against open_dets with the given cost; applies matches.
  auto run_stage = [&](const std::vector<int>& rows, double threshold, auto&& cost_of) {
    Eigen::MatrixXd cost(rows.size(), open_dets.size());
    for (int r = 0; r < static_cast<int>(rows.size()); ++r)
      for (int c = 0; c < static_cast<int>(open_dets.size()); ++c) {
        const Track& t = tracks_[rows[r]];
        const Detection& d = detections[open_dets[c]];
        cost(r, c) = (t.class_id == d.class_id) ? cost_of(t, d) : kForbidden;
      }
    const Assignment a = solve_assignment(cost, threshold);
    for (const auto& [r, c] : a.matches) {
      apply_match(tracks_[rows[r]], detections[open_dets[c]]);
      result[open_dets[c]] = tracks_[rows[r]].id;
    }
    std::vector<int> rest;
    for (int c : a.unmatched_cols) rest.push_back(open_dets[c]);
    open_dets = std::move(rest);
    std::vector<int> unmatched_rows;
    for (int r : a.unmatched_rows) unmatched_rows.push_back(rows[r]);
    return unmatched_rows;
  };

  // Stage 1: appearance fused with the motion gate (FairMOT fuse_motion).
  const bool gate = options_.motion_gate_chi2 > 0;
  const double lambda = options_.motion_lambda;
  const std::vector<int> pool_left =
      run_stage(pool, options_.embedding_distance, [&](const Track& t, const Detection& d) {
        const double e = embedding_distance(t.embedding, d.embedding);
        if (!gate || !std::isfinite(e)) return e;
        const double g = kf_.gating_distance(t.kalman, corners_to_xyah(d.box), options_.motion_gate_position_only);
        if (g > options_.motion_gate_chi2) return kForbidden;
        return lambda * e + (1 - lambda) * g;
      });

  // Stage 2: IoU for the tracks that were tracked in the previous frame.
  auto iou_cost = [](const Track& t, const Detection& d) { return iou_distance(t.box(), d.box); };
  std::vector<int> tracked_left, tentative_left;
  for (int k : pool_left) {
    if (tracks_[k].state == TrackState::kTracked) tracked_left.push_back(k);
    if (tracks_[k].state == TrackState::kTentative) tentative_left.push_back(k);
  }
  if (!options_.match_unconfirmed_by_appearance) tentative_left = unconfirmed;
  for (int k : run_stage(tracked_left, options_.iou_distance_tracked, iou_cost)) tracks_[k].state = TrackState::kLost;

  // Stage 3: tentative tracks (usually one frame old) by IoU; a tentative track that misses dies.
  std::vector<char> remove(tracks_.size(), 0);
  for (int k : run_stage(tentative_left, options_.iou_distance_unconfirmed, iou_cost)) remove[k] = 1;

  // Aging of lost tracks.
  for (int k = 0; k < static_cast<int>(tracks_.size()); ++k)
    if (tracks_[k].state == TrackState::kLost && frame_ - tracks_[k].last_frame > options_.max_lost_frames)
      remove[k] = 1;
  // Lost tracks that sit on a tracked one of the same class (FairMOT remove_duplicate_stracks). Deviation: the lost
  // one is always dropped, so the ids already returned for this frame stay valid.
  for (int p = 0; p < static_cast<int>(tracks_.size()); ++p) {
    if (tracks_[p].state != TrackState::kTracked || remove[p]) continue;
    for (int q = 0; q < static_cast<int>(tracks_.size()); ++q)
      if (tracks_[q].state == TrackState::kLost && !remove[q] && tracks_[q].class_id == tracks_[p].class_id &&
          iou_distance(tracks_[p].box(), tracks_[q].box()) < options_.duplicate_iou_distance)
        remove[q] = 1;
  }
  std::vector<Track> kept;
  kept.reserve(tracks_.size());
  for (int k = 0; k < static_cast<int>(tracks_.size()); ++k)
    if (!remove[k]) kept.push_back(std::move(tracks_[k]));
  tracks_ = std::move(kept);

  // New tracks from confident leftovers (ids increase with detection order: deterministic).
  for (int i : open_dets)
    if (detections[i].score >= options_.new_track_score) {
      start_track(detections[i]);
      result[i] = tracks_.back().id;
    }
  return result;  // tracks_ stays sorted by id: survivors keep their order, new ids are larger
}

}  // namespace wardmap::mot
