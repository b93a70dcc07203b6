// Local mapping: takes the tracker's new keyframes from a bounded queue and, for each, registers its
// observations, culls unreliable recent points, triangulates new points with covisible keyframes,
// fuses duplicates with the neighbours, runs local bundle adjustment and culls redundant keyframes.
// Two modes: inline (process_queued drains the queue on the caller's thread: deterministic), or a
// worker thread (start/stop) that maps each keyframe holding the submap's lock step by step and
// releasing it while bundle adjustment solves, so that tracking goes on meanwhile.
#pragma once

#include <atomic>
#include <condition_variable>
#include <list>
#include <memory>
#include <mutex>
#include <thread>

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
  int deferred = 0;  // keyframes mapped without fusion, BA and culling: the threaded mapper was behind
  int ba_aborted = 0;  // local BAs cut short: a keyframe waiting or wanted by the tracker (threaded)
  LocalBAResult last_ba;
  // Wall time spent per stage (seconds, summed over keyframes).
  double t_register = 0, t_cull = 0, t_triangulate = 0, t_fuse = 0, t_ba = 0, t_cull_keyframes = 0;
  // All stages together: the mapper's work.
  double total_seconds() const { return t_register + t_cull + t_triangulate + t_fuse + t_ba + t_cull_keyframes; }
};

class LocalMapper {
 public:
  LocalMapper(const FrontOptions& options, const PinholeCamera& camera);
  ~LocalMapper();
  LocalMapper(const LocalMapper&) = delete;
  LocalMapper& operator=(const LocalMapper&) = delete;

  // Call only while idle (inline, or after wait_idle()).
  void set_submap(std::shared_ptr<Submap> submap);
  // Registering a keyframe then computes its bag of words (off the tracking thread, as ORB-SLAM does);
  // call it, too, only while idle.
  void set_vocabulary(std::shared_ptr<const place::Vocabulary> vocabulary) { vocabulary_ = std::move(vocabulary); }
  // False when the queue is full: the tracker then keeps tracking and tries again later.
  bool enqueue(std::shared_ptr<KeyFrame> keyframe) { return queue_.try_push(std::move(keyframe)); }
  bool idle() const { return queue_.empty() && !busy_; }
  bool queue_full() const { return queue_.size() >= static_cast<size_t>(options_.mapping.queue_capacity); }
  size_t queued() const { return queue_.size(); }
  // Inline mode: maps every queued keyframe. Threaded mode: does nothing (the worker does it).
  void process_queued();
  // Worker thread: start() once; stop() maps what is queued, then joins. wait_idle() blocks until
  // the queue is empty and no keyframe is being mapped.
  void start();
  void stop();
  void wait_idle();
  // Threaded: waits until idle or until `seconds` have passed; true when idle. Inline: wait_idle().
  bool wait_idle_for(double seconds);
  bool threaded() const { return worker_.joinable(); }
  // The tracker wants a keyframe while the mapper is busy (ORB-SLAM's InterruptBA): the local BA
  // running now stops at its next iteration (mapping.abort_ba_when_behind).
  void interrupt_ba() { interrupt_ba_ = true; }
  void process(const std::shared_ptr<KeyFrame>& keyframe);
  // Read only when idle or stopped in threaded mode.
  const LocalMapperStats& stats() const { return stats_; }

 private:
  void register_keyframe(const std::shared_ptr<KeyFrame>& kf);
  void cull_recent_points(const std::shared_ptr<KeyFrame>& kf);
  void triangulate_with_neighbours(const std::shared_ptr<KeyFrame>& kf);
  void fuse_with_neighbours(const std::shared_ptr<KeyFrame>& kf);
  void cull_keyframes(const std::shared_ptr<KeyFrame>& kf);
  void run();

  FrontOptions options_;
  PinholeCamera camera_;
  OrbMatcher matcher_;
  std::shared_ptr<const place::Vocabulary> vocabulary_;
  std::shared_ptr<Submap> submap_;
  BoundedQueue<std::shared_ptr<KeyFrame>> queue_;
  std::list<std::shared_ptr<MapPoint>> recent_points_;
  LocalMapperStats stats_;
  std::thread worker_;
  std::atomic<bool> busy_{false};
  std::atomic<bool> interrupt_ba_{false};
  std::mutex idle_mutex_;
  std::condition_variable idle_cv_;
};

}  // namespace wardmap::slam
