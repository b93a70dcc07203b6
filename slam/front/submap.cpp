#include "slam/front/submap.h"

#include <utility>

namespace wardmap::slam {

Submap::Submap(int id, std::shared_ptr<IdSource> ids) : id_(id), ids_(std::move(ids)) {}

std::shared_ptr<KeyFrame> Submap::create_keyframe(const Frame& frame) {
  auto kf = std::make_shared<KeyFrame>(ids_->next_keyframe++, frame);
  keyframes_[kf->id()] = kf;
  if (!origin_) origin_ = kf;
  return kf;
}

std::shared_ptr<MapPoint> Submap::create_map_point(const Eigen::Vector3d& position, const KeyFrame& first) {
  auto mp = std::make_shared<MapPoint>(ids_->next_map_point++, position, first.id(), first.timestamp());
  map_points_[mp->id()] = mp;
  return mp;
}

void Submap::erase_map_point(const std::shared_ptr<MapPoint>& mp) {
  if (!mp) return;
  mp->set_bad();
  map_points_.erase(mp->id());
}

void Submap::erase_keyframe(const std::shared_ptr<KeyFrame>& kf) {
  if (!kf || kf == origin_ || kf->not_erase) return;
  std::shared_ptr<KeyFrame> parent = kf->parent();
  if (!parent || parent->bad()) {
    auto cov = kf->best_covisibles(1);
    parent = cov.empty() ? origin_ : cov.front();
  }
  const std::vector<std::shared_ptr<MapPoint>> seen = kf->map_points();
  kf->set_bad(parent);
  keyframes_.erase(kf->id());
  culled_.push_back(kf->id());
  purge_bad_points(seen);  // the points this keyframe was the last to observe
}

std::vector<KeyFrameId> Submap::take_culled() { return std::exchange(culled_, {}); }

void Submap::clear() {
  for (auto& [id, mp] : map_points_) mp->set_bad();
  map_points_.clear();
  keyframes_.clear();
  culled_.clear();
  origin_.reset();
}

void Submap::purge_bad_points() {
  for (auto it = map_points_.begin(); it != map_points_.end();) {
    if (it->second->bad()) {
      it->second->set_bad();
      it = map_points_.erase(it);
    } else {
      ++it;
    }
  }
}

void Submap::purge_bad_points(const std::vector<std::shared_ptr<MapPoint>>& candidates) {
  for (const auto& mp : candidates)
    if (mp && mp->bad()) {
      const auto it = map_points_.find(mp->id());
      if (it == map_points_.end() || it->second != mp) continue;
      mp->set_bad();
      map_points_.erase(it);
    }
}

std::vector<std::shared_ptr<KeyFrame>> Submap::recent_keyframes(size_t n) const {
  std::vector<std::shared_ptr<KeyFrame>> out;
  for (auto it = keyframes_.rbegin(); it != keyframes_.rend() && out.size() < n; ++it) out.push_back(it->second);
  return out;
}

}  // namespace wardmap::slam
