#include "slam/front/key_frame.h"

#include <algorithm>

namespace wardmap::slam {

KeyFrame::KeyFrame(KeyFrameId id, const Frame& frame)
    : id_(id),
      frame_id_(frame.id()),
      timestamp_(frame.timestamp()),
      features_(frame.shared_features()),
      map_points_(frame.map_points) {
  set_pose_cw(frame.pose_cw());
  for (size_t i = 0; i < map_points_.size(); ++i)
    if (map_points_[i] && (map_points_[i]->bad() || frame.outlier[i])) map_points_[i].reset();
}

int KeyFrame::tracked_points(int min_observations) const {
  int n = 0;
  for (const auto& mp : map_points_)
    if (mp && !mp->bad() && mp->num_observations() >= min_observations) ++n;
  return n;
}

std::vector<std::pair<KeyFrameId, KeyFrame::Connection>>::iterator KeyFrame::find_connection(KeyFrameId id) {
  return std::lower_bound(connections_.begin(), connections_.end(), id,
                          [](const auto& c, KeyFrameId k) { return c.first < k; });
}

std::vector<std::pair<KeyFrameId, KeyFrame::Connection>>::const_iterator KeyFrame::find_connection(
    KeyFrameId id) const {
  return std::lower_bound(connections_.begin(), connections_.end(), id,
                          [](const auto& c, KeyFrameId k) { return c.first < k; });
}

void KeyFrame::set_connection(KeyFrameId id, Connection c) {
  const auto it = find_connection(id);
  if (it != connections_.end() && it->first == id)
    it->second = std::move(c);
  else
    connections_.insert(it, {id, std::move(c)});
}

void KeyFrame::add_connection(const std::shared_ptr<KeyFrame>& kf, int weight) {
  set_connection(kf->id(), Connection{kf, weight});
}

void KeyFrame::erase_connection(KeyFrameId id) {
  const auto it = find_connection(id);
  if (it != connections_.end() && it->first == id) connections_.erase(it);
}

int KeyFrame::weight(KeyFrameId id) const {
  const auto it = find_connection(id);
  return it == connections_.end() || it->first != id ? 0 : it->second.weight;
}

void KeyFrame::update_connections(int min_weight) {
  std::map<KeyFrameId, std::pair<std::shared_ptr<KeyFrame>, int>> counts;
  for (const auto& mp : map_points_) {
    if (!mp || mp->bad()) continue;
    for (const auto& [id, obs] : mp->observations()) {
      if (id == id_) continue;
      auto kf = obs.keyframe.lock();
      if (!kf || kf->bad()) continue;
      auto& c = counts[id];
      c.first = kf;
      ++c.second;
    }
  }
  for (auto& [id, c] : connections_)
    if (auto kf = c.keyframe.lock(); kf && !counts.count(id)) kf->erase_connection(id_);
  connections_.clear();
  if (counts.empty()) return;
  auto self = shared_from_this();
  std::shared_ptr<KeyFrame> best;
  int best_w = 0;
  for (auto& [id, c] : counts) {
    if (c.second > best_w) {
      best_w = c.second;
      best = c.first;
    }
    if (c.second >= min_weight) {
      set_connection(id, Connection{c.first, c.second});
      c.first->add_connection(self, c.second);
    }
  }
  if (connections_.empty()) {
    set_connection(best->id(), Connection{best, best_w});
    best->add_connection(self, best_w);
  }
  if (!parent_.lock() && best && best->id() < id_) parent_ = best;
}

std::vector<std::shared_ptr<KeyFrame>> KeyFrame::best_covisibles(int n) const {
  // Ordered on (weight, id) before any weak_ptr is locked: only the neighbours returned, and the bad
  // ones ranked before them, pay for a lock (the tracker asks for the best 10 of dozens, per local
  // keyframe and frame).
  struct Ranked {
    int weight;
    KeyFrameId id;
    const std::weak_ptr<KeyFrame>* keyframe;
  };
  std::vector<Ranked> ranked;
  ranked.reserve(connections_.size());
  for (const auto& [id, c] : connections_) ranked.push_back({c.weight, id, &c.keyframe});
  std::sort(ranked.begin(), ranked.end(),
            [](const Ranked& a, const Ranked& b) { return a.weight != b.weight ? a.weight > b.weight : a.id < b.id; });
  std::vector<std::shared_ptr<KeyFrame>> out;
  for (const Ranked& r : ranked) {
    if (n > 0 && static_cast<int>(out.size()) >= n) break;
    if (auto kf = r.keyframe->lock(); kf && !kf->bad()) out.push_back(std::move(kf));
  }
  return out;
}

void KeyFrame::set_bad(const std::shared_ptr<KeyFrame>& new_parent) {
  for (auto& [id, c] : connections_)
    if (auto kf = c.keyframe.lock()) kf->erase_connection(id_);
  decltype(connections_)().swap(connections_);
  for (const auto& mp : map_points_)
    if (mp) mp->erase_observation(id_);
  decltype(map_points_)().swap(map_points_);
  parent_ = new_parent;
  if (new_parent) T_cp_ = T_cw_ * new_parent->pose_wc();
  bad_ = true;
  // Only the pose relative to the parent is used from here on (frames referring to this keyframe keep
  // it alive for the trajectory): its point slots, features and words go, so that memory follows the
  // keyframes kept, not every keyframe ever made (a camera going back and forth makes and culls them
  // without end).
  auto husk = std::make_shared<FrameFeatures>();
  husk->pyramid = features_->pyramid;
  husk->bf = features_->bf;
  features_ = std::move(husk);
  place::BowVector().swap(bow);
  place::FeatureVector().swap(feature_vector);
}

double median_scene_depth(const KeyFrame& kf) {
  std::vector<double> z;
  for (const auto& mp : kf.map_points())
    if (mp && !mp->bad()) z.push_back((kf.pose_cw() * mp->position()).z());
  if (z.empty()) return 0;
  std::nth_element(z.begin(), z.begin() + static_cast<long>(z.size() / 2), z.end());
  return z[z.size() / 2];
}

}  // namespace wardmap::slam
