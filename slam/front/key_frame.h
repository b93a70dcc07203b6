// A keyframe: a frame kept in the map, with its pose, features, map-point associations, the
// covisibility graph (keyframes sharing points, weighted by their number) and a spanning-tree parent
// used to keep poses of culled keyframes and of the frames referring to them.
#pragma once

#include <cstdint>
#include <map>
#include <memory>
#include <vector>

#include "slam/core/se3.h"
#include "slam/front/frame.h"
#include "slam/front/map_point.h"
#include "slam/place/vocabulary.h"

namespace wardmap::slam {

class KeyFrame;
// Median depth of the keyframe's map points in its camera frame (0 when it has none).
double median_scene_depth(const KeyFrame& kf);

class KeyFrame : public std::enable_shared_from_this<KeyFrame> {
 public:
  KeyFrame(KeyFrameId id, const Frame& frame);

  KeyFrameId id() const { return id_; }
  std::uint64_t frame_id() const { return frame_id_; }
  double timestamp() const { return timestamp_; }
  const FrameFeatures& features() const { return *features_; }
  size_t size() const { return features_->size(); }

  const SE3& pose_cw() const { return T_cw_; }
  const SE3& pose_wc() const { return T_wc_; }
  void set_pose_cw(const SE3& T_cw) {
    T_cw_ = T_cw;
    T_wc_ = T_cw.inverse();
  }
  Eigen::Vector3d camera_center() const { return T_wc_.translation(); }

  // Map-point associations, one slot per keypoint.
  const std::shared_ptr<MapPoint>& map_point(size_t i) const { return map_points_[i]; }
  const std::vector<std::shared_ptr<MapPoint>>& map_points() const { return map_points_; }
  void set_map_point(size_t i, std::shared_ptr<MapPoint> mp) { map_points_[i] = std::move(mp); }
  void erase_map_point(int i) {
    if (i >= 0 && static_cast<size_t>(i) < map_points_.size()) map_points_[static_cast<size_t>(i)].reset();
  }
  // Points with at least `min_observations` observations.
  int tracked_points(int min_observations) const;

  // Covisibility: rebuilt from the map points' observations; an edge needs `min_weight` shared
  // points (the strongest neighbour is always kept). Edges are mirrored in the neighbours.
  void update_connections(int min_weight = 15);
  void add_connection(const std::shared_ptr<KeyFrame>& kf, int weight);
  void erase_connection(KeyFrameId id);
  // The n neighbours with the most shared points (all when n <= 0), best first, bad ones skipped.
  std::vector<std::shared_ptr<KeyFrame>> best_covisibles(int n = 0) const;
  int weight(KeyFrameId id) const;

  // Spanning tree (parent = the covisible keyframe with most shared points when the edge was made).
  std::shared_ptr<KeyFrame> parent() const { return parent_.lock(); }
  void set_parent(const std::shared_ptr<KeyFrame>& p) { parent_ = p; }

  // Removal: the keyframe leaves the covisibility graph and its points; its pose is then kept as
  // T_cp relative to `parent` so that frames referring to it still get a pose. Its point slots,
  // features (then empty: size() is 0) and words are released.
  bool bad() const { return bad_; }
  void set_bad(const std::shared_ptr<KeyFrame>& new_parent);
  const SE3& pose_relative_to_parent() const { return T_cp_; }

  bool not_erase = false;  // set while another module relies on it (e.g. the mapper's current keyframe)
  // Scratch for build_local_map: the stamp of the last local map that took this keyframe.
  std::uint64_t local_map_stamp = 0;
  // Bag of words (empty without a vocabulary), for relocalisation; computed once, by the mapper when
  // it registers the keyframe, or by the tracker if it needs them first (both hold the submap's lock).
  place::BowVector bow;
  place::FeatureVector feature_vector;  // direct index (features per vocabulary node), for guided matching
  void compute_words(const place::Vocabulary& vocabulary) {
    if (bow.empty()) bow = vocabulary.transform(features().descriptors, &feature_vector, 2);
  }

 private:
  struct Connection {
    std::weak_ptr<KeyFrame> keyframe;
    int weight = 0;
  };
  KeyFrameId id_;
  std::uint64_t frame_id_;
  double timestamp_;
  std::shared_ptr<const FrameFeatures> features_;
  SE3 T_cw_, T_wc_;
  std::vector<std::shared_ptr<MapPoint>> map_points_;
  // Sorted by keyframe id; a flat vector (the tracker ranks the neighbours of dozens of keyframes
  // per frame, and contiguous entries cost far fewer cache misses than tree nodes).
  std::vector<std::pair<KeyFrameId, Connection>> connections_;
  // The first connection whose id is not below `id`; sets (inserts or overwrites) one connection.
  std::vector<std::pair<KeyFrameId, Connection>>::iterator find_connection(KeyFrameId id);
  std::vector<std::pair<KeyFrameId, Connection>>::const_iterator find_connection(KeyFrameId id) const;
  void set_connection(KeyFrameId id, Connection c);
  std::weak_ptr<KeyFrame> parent_;
  bool bad_ = false;
  SE3 T_cp_;
};

}  // namespace wardmap::slam
