#include "slam/front/local_map.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdint>

#include "slam/front/submap.h"

namespace wardmap::slam {

LocalMap build_local_map(const Frame& frame, const Submap& submap, const TrackingOptions& o) {
  LocalMap local;
  // Keyframes sharing points with the frame (K1), weighted by the number shared. The observing
  // keyframes' ids are gathered and counted first, so that only one weak_ptr per keyframe is locked
  // (a frame has thousands of observations over a few dozen keyframes).
  struct Observer {
    KeyFrameId id;
    const std::weak_ptr<KeyFrame>* keyframe;
  };
  std::vector<Observer> observers;
  observers.reserve(8 * frame.size());
  for (size_t i = 0; i < frame.size(); ++i) {
    const auto& mp = frame.map_points[i];
    if (!mp || mp->bad() || frame.outlier[i]) continue;
    for (const auto& [id, obs] : mp->observations()) observers.push_back({id, &obs.keyframe});
  }
  std::sort(observers.begin(), observers.end(), [](const Observer& a, const Observer& b) { return a.id < b.id; });
  // Keyframes already taken carry this call's stamp (unique across calls and trackers).
  static std::atomic<std::uint64_t> last_stamp{0};
  const std::uint64_t stamp = ++last_stamp;
  auto add = [&](const std::shared_ptr<KeyFrame>& kf) {
    if (!kf || kf->bad() || static_cast<int>(local.keyframes.size()) >= o.max_local_keyframes) return;
    if (kf->local_map_stamp == stamp) return;
    kf->local_map_stamp = stamp;
    local.keyframes.push_back(kf);
  };
  int best = 0;
  std::vector<std::pair<int, std::shared_ptr<KeyFrame>>> k1;
  for (size_t a = 0; a < observers.size();) {
    size_t b = a + 1;
    while (b < observers.size() && observers[b].id == observers[a].id) ++b;
    if (auto kf = observers[a].keyframe->lock(); kf && !kf->bad()) {
      const int shared = static_cast<int>(b - a);
      if (shared > best) {  // ties: the smallest id, as the ids are ascending
        best = shared;
        local.reference = kf;
      }
      k1.emplace_back(shared, std::move(kf));
    }
    a = b;
  }
  std::stable_sort(k1.begin(), k1.end(), [](const auto& a, const auto& b) { return a.first > b.first; });
  for (auto& [w, kf] : k1) add(kf);
  // Short-term: keyframes of the last Th_t seconds.
  for (const auto& kf : submap.recent_keyframes(static_cast<size_t>(o.max_local_keyframes)))
    if (std::abs(frame.timestamp() - kf->timestamp()) < o.short_term_seconds) add(kf);
  // Mid-term neighbours (K2): the best covisibles of K1 and their spanning-tree parents.
  const size_t n1 = local.keyframes.size();
  for (size_t i = 0; i < n1; ++i) {
    for (const auto& nb : local.keyframes[i]->best_covisibles(10)) add(nb);
    add(local.keyframes[i]->parent());
  }
  if (!local.reference && !local.keyframes.empty()) local.reference = local.keyframes.front();

  // Points: RUMI Formula 5 (short-term by time or mid-term by position).
  const Eigen::Vector3d centre = frame.camera_center();
  const double th_p2 = o.mid_term_distance * o.mid_term_distance;
  for (const auto& kf : local.keyframes)
    for (const auto& mp : kf->map_points()) {
      if (!mp || mp->bad() || mp->local_frame_id == frame.id()) continue;
      mp->local_frame_id = frame.id();
      const bool short_term = std::abs(frame.timestamp() - mp->last_seen()) < o.short_term_seconds;
      const bool mid_term = (mp->position() - centre).squaredNorm() < th_p2;
      if (short_term || mid_term) local.points.push_back(mp);
    }
  return local;
}

std::vector<ProjectionCandidate> visible_candidates(const Frame& frame,
                                                    const std::vector<std::shared_ptr<MapPoint>>& points,
                                                    const PinholeCamera& camera) {
  std::vector<ProjectionCandidate> out;
  const SE3& T_cw = frame.pose_cw();
  const Eigen::Vector3d centre = frame.camera_center();
  const FrameFeatures& f = frame.features();
  for (const auto& mp : points) {
    if (mp->bad() || mp->track_frame_id == frame.id()) continue;
    const Eigen::Vector3d pc = T_cw * mp->position();
    if (pc.z() <= 0) continue;
    const Eigen::Vector2d uv = project_pinhole(camera, pc);
    if (!camera.in_image(uv)) continue;
    const Eigen::Vector3d ray = mp->position() - centre;
    const double dist = ray.norm();
    if (dist < mp->min_distance() || dist > mp->max_distance()) continue;
    const double view_cos = ray.dot(mp->normal()) / dist;
    if (view_cos < 0.5) continue;
    ProjectionCandidate c;
    c.point = mp;
    c.pixel = uv;
    c.right_u = uv.x() - f.bf / pc.z();
    c.level = mp->predict_level(dist, *f.pyramid);
    c.view_cos = view_cos;
    mp->increase_visible();
    out.push_back(std::move(c));
  }
  return out;
}

}  // namespace wardmap::slam
