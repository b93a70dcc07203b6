// A submap: the keyframes and map points built by one uninterrupted tracking session. It owns them
// (shared_ptr); frames, keyframes and points refer to each other by weak_ptr or id. Ids come from an
// IdSource shared by every submap of an Atlas, so that ids stay unique across a later merge.
#pragma once

#include <atomic>
#include <cstdint>
#include <map>
#include <memory>
#include <mutex>
#include <unordered_map>
#include <vector>

#include "slam/front/key_frame.h"
#include "slam/front/map_point.h"

namespace wardmap::slam {

struct IdSource {
  std::atomic<std::uint64_t> next_keyframe{0};
  std::atomic<std::uint64_t> next_map_point{0};
};

class Submap {
 public:
  explicit Submap(int id, std::shared_ptr<IdSource> ids = std::make_shared<IdSource>());

  int id() const { return id_; }
  std::shared_ptr<KeyFrame> create_keyframe(const Frame& frame);
  std::shared_ptr<MapPoint> create_map_point(const Eigen::Vector3d& position, const KeyFrame& first);
  // Marks the point bad (removing it from its keyframes) and forgets it.
  void erase_map_point(const std::shared_ptr<MapPoint>& mp);
  // Culls a keyframe: it leaves the graph and its points; its pose is kept relative to its parent.
  void erase_keyframe(const std::shared_ptr<KeyFrame>& kf);
  // The ids of the keyframes culled since the last call (the tracker takes them out of its place
  // database, as ORB-SLAM's KeyFrame::SetBadFlag erases a keyframe from its KeyFrameDatabase).
  std::vector<KeyFrameId> take_culled();
  // Drops every keyframe and point (a failed initialisation starts over in the same submap).
  void clear();
  // Forgets points that became bad elsewhere (no observations left, replaced): all of them (a scan
  // of the whole map), or only those among `candidates`, the points an operation touched (the
  // mapper's hot paths: a full scan per keyframe grew with the map, 18 % of a KITTI run).
  void purge_bad_points();
  void purge_bad_points(const std::vector<std::shared_ptr<MapPoint>>& candidates);

  const std::map<KeyFrameId, std::shared_ptr<KeyFrame>>& keyframes() const { return keyframes_; }
  const std::unordered_map<MapPointId, std::shared_ptr<MapPoint>>& map_points() const { return map_points_; }
  size_t num_keyframes() const { return keyframes_.size(); }
  size_t num_map_points() const { return map_points_.size(); }
  std::shared_ptr<KeyFrame> origin() const { return origin_; }
  // The keyframes in insertion order, newest last.
  std::vector<std::shared_ptr<KeyFrame>> recent_keyframes(size_t n) const;

  // The one lock on this submap's structure, for when the LocalMapper runs on its own thread.
  std::mutex& mutex() const { return mutex_; }

 private:
  int id_;
  std::shared_ptr<IdSource> ids_;
  std::map<KeyFrameId, std::shared_ptr<KeyFrame>> keyframes_;
  std::unordered_map<MapPointId, std::shared_ptr<MapPoint>> map_points_;
  std::shared_ptr<KeyFrame> origin_;
  std::vector<KeyFrameId> culled_;
  mutable std::mutex mutex_;
};

}  // namespace wardmap::slam
