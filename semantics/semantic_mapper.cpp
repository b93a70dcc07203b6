#include "semantics/semantic_mapper.h"

#include <chrono>
#include <stdexcept>
#include <string>


namespace wardmap::semantics {

namespace {
double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}
}  // namespace

SemanticMapper::SemanticMapper(const SemanticOptions& options, Detector& detector, EmbedFn embed,
                               const slam::PinholeCamera& camera)
    : options_(options), detector_(detector), embed_(std::move(embed)), camera_(camera) {}

void SemanticMapper::add_keyframe(const KeyframeInput& kf) {
  KeyframeRecord rec{static_cast<int>(keyframes_.size()), kf.timestamp, kf.T_wc};
  keyframes_.push_back(rec);
  Eigen::Vector3d up = up_.value_or(Eigen::Vector3d::UnitZ());
  if (!up_) {
    std::vector<slam::SE3> poses;
    for (const auto& k : keyframes_) poses.push_back(k.T_wc);
    up = estimate_up(poses);
  }

  auto t0 = std::chrono::steady_clock::now();
  const std::vector<Detection> dets = detector_.detect(kf.image, kf.timestamp);
  times_.detection.push_back(seconds_since(t0));

  std::vector<Eigen::Vector4d> boxes;
  std::vector<std::string> labels;
  for (const auto& d : dets) {
    boxes.push_back(d.box);
    labels.push_back(d.label);
  }

  t0 = std::chrono::steady_clock::now();
  std::vector<Eigen::VectorXf> embeddings(dets.size());
  if (embed_ && !dets.empty()) {
    embeddings = embed_(kf.image, boxes);
    if (embeddings.size() != dets.size())
      throw std::logic_error("SemanticMapper: the embedding function gave " + std::to_string(embeddings.size()) +
                             " embeddings for " + std::to_string(dets.size()) + " boxes");
  }
  times_.embedding.push_back(seconds_since(t0));

  t0 = std::chrono::steady_clock::now();
  std::vector<std::optional<ObjectPose>> side_cut_poses;
  std::vector<bool> duplicates;
  auto poses = measure_keyframe_poses(kf.depth, camera_, kf.T_wc, boxes, labels, up, options_, &side_cut_poses,
                                      &duplicates);
  for (size_t i = 0; i < dets.size(); ++i) {
    if (duplicates[i]) continue;  // one object detected twice: one measurement
    ObjectMeasurement m;
    m.id = static_cast<int>(measurements_.size());
    m.keyframe = rec.index;
    m.timestamp = kf.timestamp;
    m.box = dets[i].box;
    m.label = dets[i].label;
    m.score = dets[i].score;
    m.embedding = std::move(embeddings[i]);
    m.gt_instance = dets[i].gt_instance;
    m.pose = std::move(poses[i]);
    m.side_cut_pose = std::move(side_cut_poses[i]);
    measurements_.push_back(std::move(m));
  }
  times_.measurement.push_back(seconds_since(t0));
}

std::vector<std::vector<int>> SemanticMapper::make_groups() const {
  KeyframeGrouper grouper(options_.groups);
  for (const auto& k : keyframes_) grouper.add_keyframe(k.index);
  grouper.flush();
  std::vector<std::vector<int>> groups;
  for (int n = 0; n < grouper.num_groups(); ++n) groups.push_back(grouper.group(n));
  return groups;
}

AssociationResult SemanticMapper::associate(const std::vector<std::vector<int>>& groups,
                                            const SemanticOptions& options) const {
  KeyframeViews views{camera_, {}};
  for (const auto& k : keyframes_) views.T_wc.push_back(k.T_wc);
  return associate_objects(measurements_, groups, options, &views);
}

AssociationResult SemanticMapper::build_map() {
  groups_ = make_groups();
  AssociationResult r = associate(groups_, options_);
  times_.mot = r.mot_seconds;
  times_.hdp = r.hdp_seconds;
  times_.pose_selection = r.pose_selection_seconds;
  return r;
}

AssociationResult SemanticMapper::build_map(const std::string& mode) const {
  if (mode != "hierarchical" && mode != "hdp-only")
    throw std::invalid_argument("SemanticMapper::build_map: association mode must be hierarchical or hdp-only, got '" +
                                mode + "'");
  SemanticOptions options = options_;
  options.association.mode = mode;
  return associate(make_groups(), options);
}

}  // namespace wardmap::semantics
