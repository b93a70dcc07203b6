#include "slam/front/local_mapper.h"

#include <chrono>
#include <cmath>
#include <unordered_set>

#include "slam/front/pose_optimizer.h"
#include "slam/front/submap.h"
#include "slam/front/triangulation.h"

namespace wardmap::slam {

LocalMapper::LocalMapper(const FrontOptions& options, const PinholeCamera& camera)
    : options_(options),
      camera_(camera),
      matcher_(options.matcher, camera),
      queue_(static_cast<size_t>(options.mapping.queue_capacity)) {}

LocalMapper::~LocalMapper() { stop(); }

void LocalMapper::start() {
  if (worker_.joinable()) return;
  worker_ = std::thread([this] { run(); });
}

void LocalMapper::stop() {
  if (!worker_.joinable()) return;
  queue_.close();
  worker_.join();
}

void LocalMapper::run() {
  while (auto kf = queue_.pop()) {
    busy_ = true;
    process(*kf);
    {
      std::lock_guard<std::mutex> lock(idle_mutex_);
      busy_ = false;
    }
    idle_cv_.notify_all();
  }
  idle_cv_.notify_all();
}

void LocalMapper::wait_idle() {
  if (!worker_.joinable()) {
    process_queued();
    return;
  }
  std::unique_lock<std::mutex> lock(idle_mutex_);
  idle_cv_.wait(lock, [this] { return queue_.empty() && !busy_; });
}

bool LocalMapper::wait_idle_for(double seconds) {
  if (!worker_.joinable()) {
    process_queued();
    return true;
  }
  std::unique_lock<std::mutex> lock(idle_mutex_);
  return idle_cv_.wait_for(lock, std::chrono::duration<double>(std::max(0.0, seconds)),
                           [this] { return queue_.empty() && !busy_; });
}

void LocalMapper::set_submap(std::shared_ptr<Submap> submap) {
  submap_ = std::move(submap);
  recent_points_.clear();
}

void LocalMapper::process_queued() {
  if (worker_.joinable()) return;
  while (auto kf = queue_.try_pop()) process(*kf);
}

void LocalMapper::process(const std::shared_ptr<KeyFrame>& kf) {
  interrupt_ba_ = false;  // a request made before this keyframe is not for its BA
  if (!submap_) return;
  // Threaded: hold the submap's lock step by step (the tracker holds it for a whole frame) and let
  // the tracker in between steps. Inline: the caller already is the tracker.
  std::unique_lock<std::mutex> lock;
  if (worker_.joinable()) lock = std::unique_lock<std::mutex>(submap_->mutex());
  if (kf->bad()) return;
  kf->not_erase = true;
  auto t0 = std::chrono::steady_clock::now();
  auto lap = [&t0, &lock](double& total) {
    const auto t1 = std::chrono::steady_clock::now();
    total += std::chrono::duration<double>(t1 - t0).count();
    if (lock.owns_lock()) {
      lock.unlock();
      std::this_thread::yield();
      lock.lock();
    }
    t0 = std::chrono::steady_clock::now();
  };
  register_keyframe(kf);
  lap(stats_.t_register);
  cull_recent_points(kf);
  lap(stats_.t_cull);
  triangulate_with_neighbours(kf);
  lap(stats_.t_triangulate);
  // As ORB-SLAM's local mapping does: while more keyframes wait (the worker is behind the tracker),
  // fusion, local BA and keyframe culling are left for later keyframes; the tracker needs the
  // waiting keyframes' points first. Inline mapping never has keyframes waiting here.
  const auto behind = [this] { return worker_.joinable() && !queue_.empty(); };
  if (!behind()) fuse_with_neighbours(kf);
  else ++stats_.deferred;
  lap(stats_.t_fuse);
  if (!behind()) {
    if (submap_->num_keyframes() > 2) {
      stats_.last_ba = local_bundle_adjustment(kf, *submap_, camera_, options_, lock.owns_lock() ? &lock : nullptr,
                                               options_.mapping.abort_ba_when_behind
                                                   ? std::function<bool()>([&] { return behind() || interrupt_ba_; })
                                                   : std::function<bool()>());
      if (stats_.last_ba.aborted) ++stats_.ba_aborted;
    }
    lap(stats_.t_ba);
    if (options_.mapping.keyframe_culling) cull_keyframes(kf);
    lap(stats_.t_cull_keyframes);
  }
  kf->not_erase = false;
  ++stats_.keyframes;
}

void LocalMapper::register_keyframe(const std::shared_ptr<KeyFrame>& kf) {
  if (vocabulary_) kf->compute_words(*vocabulary_);
  for (size_t i = 0; i < kf->size(); ++i) {
    const auto& mp = kf->map_point(i);
    if (!mp || mp->bad()) continue;
    if (!mp->observed_by(kf->id())) {
      mp->add_observation(kf, static_cast<int>(i));
      mp->update_normal_and_depth();
      mp->update_descriptor();
    } else if (mp->first_keyframe() == kf->id()) {
      recent_points_.push_back(mp);  // created from this keyframe's depth
    }
  }
  kf->update_connections();
}

void LocalMapper::cull_recent_points(const std::shared_ptr<KeyFrame>& kf) {
  const MappingOptions& m = options_.mapping;
  for (auto it = recent_points_.begin(); it != recent_points_.end();) {
    const auto& mp = *it;
    const KeyFrameId age = kf->id() - mp->first_keyframe();
    if (mp->bad()) {  // NOLINT(bugprone-branch-clone): the same erase as a point past probation
      it = recent_points_.erase(it);
    } else if (mp->found_ratio() < m.recent_found_ratio ||
               (age >= 2 && mp->num_observations() <
                                (options_.monocular ? m.recent_min_observations_mono : m.recent_min_observations))) {
      submap_->erase_map_point(mp);
      ++stats_.culled_points;
      it = recent_points_.erase(it);
    } else if (age >= 3) {
      it = recent_points_.erase(it);  // survived its probation
    } else {
      ++it;
    }
  }
}

void LocalMapper::triangulate_with_neighbours(const std::shared_ptr<KeyFrame>& kf) {
  const bool mono = options_.monocular;
  const int n = mono ? options_.mapping.triangulation_neighbours_mono : options_.mapping.triangulation_neighbours;
  if (n <= 0) return;
  const FrameFeatures& f1 = kf->features();
  const double cos_max =
      std::cos((mono ? options_.mapping.min_parallax_deg_mono : options_.mapping.min_parallax_deg) * M_PI / 180.0);
  const double chi2_mono = options_.tracking.chi2_mono;
  for (const auto& nb : kf->best_covisibles(n)) {
    const double baseline = (nb->camera_center() - kf->camera_center()).norm();
    if (mono) {
      const double depth = median_scene_depth(*nb);
      if (depth <= 0 || baseline / depth < options_.mapping.min_baseline_depth_ratio) continue;
    } else if (baseline < options_.tracking.virtual_baseline) {
      continue;  // RGB-D depth is better here
    }
    const FrameFeatures& f2 = nb->features();
    for (const auto& [i1, i2] : matcher_.search_for_triangulation(*kf, *nb)) {
      const size_t a = static_cast<size_t>(i1), b = static_cast<size_t>(i2);
      const Eigen::Vector3d x1((f1.points[a].x() - camera_.cx) / camera_.fx,
                               (f1.points[a].y() - camera_.cy) / camera_.fy, 1);
      const Eigen::Vector3d x2((f2.points[b].x() - camera_.cx) / camera_.fx,
                               (f2.points[b].y() - camera_.cy) / camera_.fy, 1);
      const Eigen::Vector3d r1 = kf->pose_wc().rotation() * x1, r2 = nb->pose_wc().rotation() * x2;
      const double ray_cos = r1.dot(r2) / (r1.norm() * r2.norm());
      std::optional<Eigen::Vector3d> X;
      if (ray_cos < cos_max) X = triangulate_dlt(x1, x2, kf->pose_cw(), nb->pose_cw());
      if (!X && f1.depth[a] > 0 && f1.depth[a] <= options_.tracking.close_depth) {
        const double d = f1.depth[a];
        X = kf->pose_wc() * Eigen::Vector3d(x1 * d);
      }
      if (!X) continue;
      // In front of both cameras, reprojection within chi2, distance ratio consistent with the scales.
      const Eigen::Vector3d p1 = kf->pose_cw() * *X, p2 = nb->pose_cw() * *X;
      if (p1.z() <= 0 || p2.z() <= 0) continue;
      const PoseObservation o1{*X, f1.points[a], f1.right_u[a],
                               f1.pyramid->inv_scale[static_cast<size_t>(f1.levels[a])]};
      const PoseObservation o2{*X, f2.points[b], f2.right_u[b],
                               f2.pyramid->inv_scale[static_cast<size_t>(f2.levels[b])]};
      const double th1 = o1.right_u >= 0 ? options_.tracking.chi2_stereo : chi2_mono;
      const double th2 = o2.right_u >= 0 ? options_.tracking.chi2_stereo : chi2_mono;
      if (observation_chi2(kf->pose_cw(), o1, camera_, f1.bf) > th1) continue;
      if (observation_chi2(nb->pose_cw(), o2, camera_, f2.bf) > th2) continue;
      const double d1 = (*X - kf->camera_center()).norm(), d2 = (*X - nb->camera_center()).norm();
      if (d1 <= 0 || d2 <= 0) continue;
      const double ratio_scale =
          f1.pyramid->scale[static_cast<size_t>(f1.levels[a])] / f2.pyramid->scale[static_cast<size_t>(f2.levels[b])];
      const double ratio_dist = d2 / d1;
      const double factor = 1.5 * f1.pyramid->scale_factor;
      if (ratio_dist * factor < ratio_scale || ratio_dist > ratio_scale * factor) continue;
      auto mp = submap_->create_map_point(*X, *kf);
      mp->add_observation(kf, i1);
      mp->add_observation(nb, i2);
      kf->set_map_point(a, mp);
      nb->set_map_point(b, mp);
      mp->update_descriptor();
      mp->update_normal_and_depth();
      recent_points_.push_back(mp);
      ++stats_.triangulated;
    }
  }
}

void LocalMapper::fuse_with_neighbours(const std::shared_ptr<KeyFrame>& kf) {
  const int n = options_.mapping.fuse_neighbours;
  if (n <= 0) return;
  std::vector<std::shared_ptr<KeyFrame>> targets;
  std::unordered_set<KeyFrameId> seen{kf->id()};
  for (const auto& nb : kf->best_covisibles(n)) {
    if (seen.insert(nb->id()).second) targets.push_back(nb);
    for (const auto& nb2 : nb->best_covisibles(5))
      if (seen.insert(nb2->id()).second) targets.push_back(nb2);
  }
  const double chi2_m = options_.tracking.chi2_mono, chi2_s = options_.tracking.chi2_stereo;
  // The keyframe's points into the neighbours...
  std::vector<std::shared_ptr<MapPoint>> own;
  for (const auto& mp : kf->map_points())
    if (mp && !mp->bad()) own.push_back(mp);
  for (const auto& t : targets) stats_.fused += matcher_.fuse(t, own, 3.0, chi2_m, chi2_s, *submap_);
  // ...and the neighbours' points into the keyframe.
  std::vector<std::shared_ptr<MapPoint>> theirs;
  std::unordered_set<MapPointId> ids;
  for (const auto& t : targets)
    for (const auto& mp : t->map_points())
      if (mp && !mp->bad() && ids.insert(mp->id()).second) theirs.push_back(mp);
  stats_.fused += matcher_.fuse(kf, theirs, 3.0, chi2_m, chi2_s, *submap_);
  for (const auto& mp : kf->map_points())
    if (mp && !mp->bad()) {
      mp->update_descriptor();
      mp->update_normal_and_depth();
    }
  kf->update_connections();
}

void LocalMapper::cull_keyframes(const std::shared_ptr<KeyFrame>& kf) {
  const MappingOptions& m = options_.mapping;
  for (const auto& nb : kf->best_covisibles()) {
    if (nb == submap_->origin() || nb->not_erase) continue;
    const FrameFeatures& f = nb->features();
    int close_points = 0, redundant = 0;
    for (size_t i = 0; i < nb->size(); ++i) {
      const auto& mp = nb->map_point(i);
      if (!mp || mp->bad()) continue;
      // RGB-D: only close points count (ORB-SLAM); monocular: all of them.
      if (!options_.monocular && (f.depth[i] <= 0 || f.depth[i] > options_.tracking.close_depth)) continue;
      ++close_points;
      if (mp->num_observations() <= m.redundant_observers) continue;
      const int level = f.levels[i];
      int observers = 0;
      for (const auto& [id, obs] : mp->observations()) {
        if (id == nb->id()) continue;
        auto other = obs.keyframe.lock();
        if (!other || other->bad()) continue;
        if (other->features().levels[static_cast<size_t>(obs.index)] <= level + 1 &&
            ++observers >= m.redundant_observers)
          break;
      }
      if (observers >= m.redundant_observers) ++redundant;
    }
    if (close_points > 0 && redundant > m.redundant_ratio * close_points) {
      submap_->erase_keyframe(nb);
      ++stats_.culled_keyframes;
    }
  }
}

}  // namespace wardmap::slam
