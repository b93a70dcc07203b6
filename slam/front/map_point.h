// A 3-D map point: position, the keyframes observing it (non-owning), a representative ORB
// descriptor, the mean viewing direction and the distance range where it is recognisable, and the
// visible / found counters used to cull unreliable points. Owned by its Submap (shared_ptr).
#pragma once

#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <memory>
#include <opencv2/core.hpp>
#include <utility>
#include <vector>

#include "slam/front/descriptor_distance.h"
#include "slam/front/scale_pyramid.h"

namespace wardmap::slam {

class KeyFrame;
using KeyFrameId = std::uint64_t;
using MapPointId = std::uint64_t;

struct Observation {
  std::weak_ptr<KeyFrame> keyframe;
  int index = -1;  // keypoint index in that keyframe
};

class MapPoint {
  // The fields the tracker reads for every point of its local map on every frame come first: the
  // object's first 104 bytes (build_local_map, visible_candidates), then the descriptor the
  // projection search reads (bytes 104-137 of 200). They were spread over 264 bytes, and a cache
  // miss per point was most of build_local_map's time.
 public:
  // Scratch for the tracker's local-map search (valid for the frame id stored beside it).
  std::uint64_t track_frame_id = UINT64_MAX;  // frame that matched it (avoid duplicate search)
  std::uint64_t local_frame_id = UINT64_MAX;  // frame whose local map holds it

 private:
  bool bad_ = false;
  int visible_ = 1, found_ = 1;
  double last_seen_ = 0;
  Eigen::Vector3d position_;
  Eigen::Vector3d normal_ = Eigen::Vector3d::Zero();
  double min_distance_ = 0, max_distance_ = 0;
  // The representative descriptor, inline: a cv::Mat would add its header and a heap block to
  // each read.
  bool has_descriptor_ = false;
  std::array<uchar, kDescriptorBytes> descriptor_{};

 public:
  MapPoint(MapPointId id, const Eigen::Vector3d& position, KeyFrameId first_keyframe, double first_timestamp);

  MapPointId id() const { return id_; }
  KeyFrameId first_keyframe() const { return first_keyframe_; }
  const Eigen::Vector3d& position() const { return position_; }
  void set_position(const Eigen::Vector3d& p) { position_ = p; }

  // Sorted by keyframe id. A flat vector rather than a std::map: the tracker walks the observations
  // of every matched point on every frame, and one contiguous block per point costs far fewer cache
  // misses than a tree node per observation.
  using Observations = std::vector<std::pair<KeyFrameId, Observation>>;
  const Observations& observations() const { return observations_; }
  int num_observations() const { return static_cast<int>(observations_.size()); }
  void add_observation(const std::shared_ptr<KeyFrame>& kf, int index);
  void erase_observation(KeyFrameId kf);
  bool observed_by(KeyFrameId kf) const { return index_in(kf) >= 0; }
  int index_in(KeyFrameId kf) const;

  // Representative descriptor: the observation's descriptor with the least median distance to the others.
  void update_descriptor();
  // Its kDescriptorBytes bytes, or nullptr before the first update or set.
  const uchar* descriptor() const { return has_descriptor_ ? descriptor_.data() : nullptr; }
  void set_descriptor(const uchar* d);

  // Mean viewing direction and [min, max] recognisable distance from the observations.
  void update_normal_and_depth();
  const Eigen::Vector3d& normal() const { return normal_; }
  double min_distance() const { return 0.8 * min_distance_; }
  double max_distance() const { return 1.2 * max_distance_; }
  int predict_level(double distance, const ScalePyramid& pyramid) const {
    return pyramid.predict_level(distance, max_distance_);
  }

  // Tracking statistics: frames where it was in view / where it was matched.
  void increase_visible(int n = 1) { visible_ += n; }
  void increase_found(int n = 1) { found_ += n; }
  int visible() const { return visible_; }
  int found() const { return found_; }
  double found_ratio() const { return visible_ > 0 ? static_cast<double>(found_) / visible_ : 0.0; }

  // Timestamp of the latest frame that matched it (RUMI Formula 5, short-term association).
  double last_seen() const { return last_seen_; }
  void set_last_seen(double t) { last_seen_ = t; }

  // Removal: drops the point from every observing keyframe. `replaced_by` is kept for frames still
  // holding this point.
  bool bad() const { return bad_; }
  void set_bad();
  // Moves every observation to `other` (which must not be bad) and marks this point bad.
  void replace_with(const std::shared_ptr<MapPoint>& other);
  std::shared_ptr<MapPoint> replaced_by() const { return replaced_by_.lock(); }

 private:
  MapPointId id_;
  KeyFrameId first_keyframe_;
  Observations observations_;
  std::weak_ptr<MapPoint> replaced_by_;
};

}  // namespace wardmap::slam
