// Local mapping: takes the tracker's new keyframes from a bounded queue and, for each, registers its
// observations, culls unreliable recent points, triangulates new points with covisible keyframes,
// fuses duplicates with the neighbours, runs local bundle adjustment and culls redundant keyframes.
// This milestone drains the queue on the caller's thread (process_queued), which is also the
// deterministic mode; a worker thread only needs to call process_queued under the submap's lock.
#pragma once

#include <list>
#include <memory>

#include "slam/core/camera.h"
#include "slam/front/bounded_queue.h"
#include "slam/front/front_options.h"
#include "slam/front/key_frame.h"
#include "slam/front/local_bundle_adjustment.h"
#include "slam/front/orb_matcher.h"

namespace wardmap::slam {

class Submap;

struct LocalMapperStats {
  int keyframes = 0;
  int triangulated = 0;
  int culled_points = 0;
  int culled_keyframes = 0;
  int fused = 0;
  LocalBAResult last_ba;
  // Wall time spent per stage (seconds, summed over keyframes).
  double t_register = 0, t_cull = 0, t_triangulate = 0, t_fuse = 0, t_ba = 0, t_cull_keyframes = 0;
};

class LocalMapper {
 public:
  LocalMapper(const FrontOptions& options, const PinholeCamera& camera);

  void set_submap(std::shared_ptr<Submap> submap);
  // False when the queue is full: the tracker then keeps tracking and tries again later.
  bool enqueue(std::shared_ptr<KeyFrame> keyframe) { return queue_.try_push(std::move(keyframe)); }
  bool idle() const { return queue_.empty(); }
  // Maps every queued keyframe.
  void process_queued();
  void process(const std::shared_ptr<KeyFrame>& keyframe);
  const LocalMapperStats& stats() const { return stats_; }

 private:
  void register_keyframe(const std::shared_ptr<KeyFrame>& kf);
  void cull_recent_points(const std::shared_ptr<KeyFrame>& kf);
  void triangulate_with_neighbours(const std::shared_ptr<KeyFrame>& kf);
  void fuse_with_neighbours(const std::shared_ptr<KeyFrame>& kf);
  void cull_keyframes(const std::shared_ptr<KeyFrame>& kf);

  FrontOptions options_;
  PinholeCamera camera_;
  OrbMatcher matcher_;
  std::shared_ptr<Submap> submap_;
  BoundedQueue<std::shared_ptr<KeyFrame>> queue_;
  std::list<std::shared_ptr<MapPoint>> recent_points_;
  LocalMapperStats stats_;
};

}  // namespace wardmap::slam
