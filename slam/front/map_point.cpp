#include "slam/front/map_point.h"

#include <algorithm>
#include <vector>

#include "slam/front/descriptor_distance.h"
#include "slam/front/key_frame.h"

namespace wardmap::slam {

MapPoint::MapPoint(MapPointId id, const Eigen::Vector3d& position, KeyFrameId first_keyframe, double first_timestamp)
    : last_seen_(first_timestamp), position_(position), id_(id), first_keyframe_(first_keyframe) {}

namespace {

// The first observation whose keyframe id is not below `id`.
template <typename Vector>
auto lower_bound_id(Vector& observations, KeyFrameId id) {
  return std::lower_bound(observations.begin(), observations.end(), id,
                          [](const auto& o, KeyFrameId k) { return o.first < k; });
}

}  // namespace

void MapPoint::add_observation(const std::shared_ptr<KeyFrame>& kf, int index) {
  const auto it = lower_bound_id(observations_, kf->id());
  if (it != observations_.end() && it->first == kf->id())
    it->second = Observation{kf, index};
  else
    observations_.insert(it, {kf->id(), Observation{kf, index}});
}

void MapPoint::erase_observation(KeyFrameId kf) {
  const auto it = lower_bound_id(observations_, kf);
  if (it != observations_.end() && it->first == kf) observations_.erase(it);
  if (observations_.empty()) bad_ = true;
}

int MapPoint::index_in(KeyFrameId kf) const {
  const auto it = lower_bound_id(observations_, kf);
  return it == observations_.end() || it->first != kf ? -1 : it->second.index;
}

void MapPoint::update_descriptor() {
  std::vector<const uchar*> ds;
  for (const auto& [id, obs] : observations_)
    if (auto kf = obs.keyframe.lock(); kf && !kf->bad())
      ds.push_back(kf->features().descriptor(static_cast<size_t>(obs.index)));
  if (ds.empty()) return;
  const size_t n = ds.size();
  std::vector<int> dist(n * n, 0);
  for (size_t i = 0; i < n; ++i)
    for (size_t j = i + 1; j < n; ++j) dist[i * n + j] = dist[j * n + i] = descriptor_distance(ds[i], ds[j]);
  size_t best = 0;
  int best_median = INT32_MAX;
  std::vector<int> row(n);
  for (size_t i = 0; i < n; ++i) {
    std::copy(dist.begin() + static_cast<long>(i * n), dist.begin() + static_cast<long>((i + 1) * n), row.begin());
    std::nth_element(row.begin(), row.begin() + static_cast<long>((n - 1) / 2), row.end());
    const int median = row[(n - 1) / 2];
    if (median < best_median) {
      best_median = median;
      best = i;
    }
  }
  set_descriptor(ds[best]);
}

void MapPoint::set_descriptor(const uchar* d) {
  std::copy(d, d + descriptor_.size(), descriptor_.begin());
  has_descriptor_ = true;
}

void MapPoint::update_normal_and_depth() {
  Eigen::Vector3d normal = Eigen::Vector3d::Zero();
  std::shared_ptr<KeyFrame> reference;
  int n = 0;
  for (const auto& [id, obs] : observations_) {
    auto kf = obs.keyframe.lock();
    if (!kf || kf->bad()) continue;
    if (!reference) reference = kf;  // the oldest observing keyframe (lowest id)
    normal += (position_ - kf->camera_center()).normalized();
    ++n;
  }
  if (!reference) return;
  normal_ = (normal / n).normalized();
  const double dist = (position_ - reference->camera_center()).norm();
  const auto& f = reference->features();
  const int level = f.levels[static_cast<size_t>(index_in(reference->id()))];
  const ScalePyramid& pyr = *f.pyramid;
  max_distance_ = dist * pyr.scale[static_cast<size_t>(level)];
  min_distance_ = max_distance_ / pyr.scale.back();
}

void MapPoint::set_bad() {
  bad_ = true;
  auto obs = std::move(observations_);
  observations_.clear();
  for (const auto& [id, o] : obs)
    if (auto kf = o.keyframe.lock()) kf->erase_map_point(o.index);
}

void MapPoint::replace_with(const std::shared_ptr<MapPoint>& other) {
  if (!other || other.get() == this) return;
  auto obs = std::move(observations_);
  observations_.clear();
  bad_ = true;
  replaced_by_ = other;
  for (const auto& [id, o] : obs) {
    auto kf = o.keyframe.lock();
    if (!kf) continue;
    if (!other->observed_by(id)) {
      kf->set_map_point(o.index, other);
      other->add_observation(kf, o.index);
    } else {
      kf->erase_map_point(o.index);
    }
  }
  other->increase_visible(visible_);
  other->increase_found(found_);
  other->update_descriptor();
}

}  // namespace wardmap::slam
