// The semantic layer fed keyframe by keyframe (ARCHITECTURE.md "SemanticMapper"): detection,
// embedding and object measurement per keyframe; keyframe groups, MOT inside groups, HDP across
// groups and landmark pose selection when the map is asked for.
#pragma once

#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "semantics/detection/detection.h"
#include "semantics/keyframe_groups.h"
#include "semantics/object_association.h"
#include "semantics/object_measurement.h"
#include "semantics/options.h"
#include "slam/core/camera.h"

namespace wardmap::semantics {

struct KeyframeInput {
  double timestamp = 0;
  cv::Mat image;   // BGR or grey
  cv::Mat depth;   // CV_32F metres; empty for monocular input
  slam::SE3 T_wc;  // camera-to-world
};

struct KeyframeRecord {
  int index = -1;
  double timestamp = 0;
  slam::SE3 T_wc;
};

// Seconds spent per stage; per-keyframe lists for the keyframe stages, totals for the map stages.
struct StageTimes {
  std::vector<double> detection, embedding, measurement;
  double mot = 0, hdp = 0, pose_selection = 0;
};

class SemanticMapper {
 public:
  // L2-normalised appearance embeddings of boxes in one image, one per box, in order; an empty one
  // means no appearance term for that box. One call per keyframe, so that an embedder can run the
  // crops at once (Embedder::embed_all).
  using EmbedFn = std::function<std::vector<Eigen::VectorXf>(const cv::Mat&, const std::vector<Eigen::Vector4d>&)>;

  SemanticMapper(const SemanticOptions& options, Detector& detector, EmbedFn embed, const slam::PinholeCamera& camera);

  // The world's up direction; when never set, it is estimated from the keyframe poses so far.
  void set_up(const Eigen::Vector3d& up) { up_ = up.normalized(); }
  void add_keyframe(const KeyframeInput& keyframe);
  // Groups, MOT, HDP and pose selection over everything added so far, in the options' association
  // mode; records the stage times.
  AssociationResult build_map();
  // The same measurements and keyframe groups associated in another mode ("hdp-only": the HDP-SLAM
  // baseline beside the hierarchical map); the same result as a mapper built with that mode, and
  // no stage times recorded.
  AssociationResult build_map(const std::string& mode) const;

  const std::vector<ObjectMeasurement>& measurements() const { return measurements_; }
  const std::vector<KeyframeRecord>& keyframes() const { return keyframes_; }
  const std::vector<std::vector<int>>& groups() const { return groups_; }
  const StageTimes& times() const { return times_; }

 private:
  std::vector<std::vector<int>> make_groups() const;
  AssociationResult associate(const std::vector<std::vector<int>>& groups, const SemanticOptions& options) const;

  SemanticOptions options_;
  Detector& detector_;
  EmbedFn embed_;
  slam::PinholeCamera camera_;
  std::optional<Eigen::Vector3d> up_;
  std::vector<ObjectMeasurement> measurements_;
  std::vector<KeyframeRecord> keyframes_;
  std::vector<std::vector<int>> groups_;
  StageTimes times_;
};

}  // namespace wardmap::semantics
