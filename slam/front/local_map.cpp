#include "slam/front/local_map.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <unordered_set>

#include "slam/front/submap.h"

namespace wardmap::slam {

LocalMap build_local_map(const Frame& frame, const Submap& submap, const TrackingOptions& o) {
  LocalMap local;
  // Keyframes sharing points with the frame (K1), weighted by the number shared.
  std::map<KeyFrameId, std::pair<std::shared_ptr<KeyFrame>, int>> shared;
  for (size_t i = 0; i < frame.size(); ++i) {
    const auto& mp = frame.map_points[i];
    if (!mp || mp->bad() || frame.outlier[i]) continue;
    for (const auto& [id, obs] : mp->observations())
      if (auto kf = obs.keyframe.lock(); kf && !kf->bad()) {
        auto& s = shared[id];
        s.first = kf;
        ++s.second;
      }
  }
  std::unordered_set<KeyFrameId> in_map;
  auto add = [&](const std::shared_ptr<KeyFrame>& kf) {
    if (!kf || kf->bad() || static_cast<int>(local.keyframes.size()) >= o.max_local_keyframes) return;
    if (in_map.insert(kf->id()).second) local.keyframes.push_back(kf);
  };
  int best = 0;
  std::vector<std::pair<int, std::shared_ptr<KeyFrame>>> k1;
  for (auto& [id, s] : shared) {
    k1.emplace_back(s.second, s.first);
    if (s.second > best) {
      best = s.second;
      local.reference = s.first;
    }
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
