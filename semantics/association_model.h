// The model the HDP Gibbs sampler (hdp/) uses to associate group objects across keyframe groups
// (Assoc. III-A.2): the prior that group object O^G_{n,i} joins landmark k is the largest GMM
// probability of O^G_{n,i}'s measurements under k's GMM (Assoc. Eq. 2-3: the paper compares two group
// objects; a landmark's GMM is the equal-weight mixture of its group objects' GMMs), times 1.5 when
// they share measurements in overlapping keyframes; appearance (embedding cosine) and class enter
// the likelihood.
#pragma once

#include <limits>
#include <vector>

#include "hdp/crf_model.h"
#include "hdp/gaussian_mixture.h"
#include "semantics/object_measurement.h"
#include "semantics/options.h"

namespace wardmap::semantics {

// One group object O^G_{n,i}: the measurements MOT tied together inside keyframe group n (or, in the
// HDP-only baseline, a single measurement of one keyframe).
struct GroupObject {
  int group = -1;
  std::string label;
  std::vector<int> measurements;         // ids, sorted
  std::vector<std::pair<int, int>> keyframe_measurements;  // (keyframe, measurement id), sorted
  std::vector<Eigen::VectorXd> features;  // 6-D pose features of the measurements with a pose
  Eigen::VectorXf embedding;              // normalised mean of the measurements' embeddings
};

// 6-D pose feature of a measurement (Assoc. Eq. 2): world position and rotation vector.
Eigen::VectorXd pose_feature(const ObjectPose& pose);

// The sorted (keyframe, measurement id) list of measurements `ids`.
std::vector<std::pair<int, int>> keyframe_measurements_of(const std::vector<int>& ids,
                                                          const std::vector<ObjectMeasurement>& ms);

// Whether two objects were measured as different detections of one keyframe, so are two objects
// (a detector gives one box per object and keyframe). Takes sorted (keyframe, id) lists.
bool detected_apart_in_one_keyframe(const std::vector<std::pair<int, int>>& a,
                                    const std::vector<std::pair<int, int>>& b);
// In how many keyframes they were (counting stops at `stop_at`).
int keyframes_detected_apart(const std::vector<std::pair<int, int>>& a, const std::vector<std::pair<int, int>>& b,
                             int stop_at = std::numeric_limits<int>::max());
// Whether they were, in at least `min_share` (> 0) of the keyframes of the one seen in fewer.
bool detected_apart_in_share(const std::vector<std::pair<int, int>>& a, const std::vector<std::pair<int, int>>& b,
                             double min_share);

class AssociationModel : public hdp::CrfModel {
 public:
  // groups[j][i] = index into `objects` of item i of group j. Objects must outlive the model.
  AssociationModel(const std::vector<GroupObject>& objects, const std::vector<std::vector<int>>& groups,
                   const AssociationOptions& options);

  double log_predictive(const hdp::ItemRef& item, const std::vector<hdp::ItemRef>& dish_members) const override;
  double log_predictive_new(const hdp::ItemRef& item) const override;
  // The chain rule over the members (CrfModel's), less the spread of the members' mean positions
  // when options.compactness_weight > 0. Scores whole states only (MAP choice, suffix swaps).
  double log_marginal(const std::vector<hdp::ItemRef>& members) const override;
  // Different classes, or different measurements in one keyframe (two detections at once are two
  // objects).
  bool cannot_link(const hdp::ItemRef& a, const hdp::ItemRef& b) const override;

  // log of the prior term alone (max GMM probability, overlap boost) of `item` joining `member`.
  double log_prior(int item_object, int member_object) const;
  // log of the prior term under the mixture of all members' GMMs (options.landmark_mixture).
  double log_mixture_prior(int item_object, const std::vector<hdp::ItemRef>& members) const;

 private:
  const GroupObject& object(const hdp::ItemRef& r) const { return objects_[groups_[r.group][r.item]]; }
  double appearance_term(const Eigen::VectorXf& a, const Eigen::VectorXf& b) const;

  const std::vector<GroupObject>& objects_;
  std::vector<std::vector<int>> groups_;
  AssociationOptions options_;
  std::vector<hdp::GaussianMixture> gmms_;  // per object (Assoc. Eq. 2)
  double log_new_ = 0;                       // GMM log density at new_landmark_distance
};

}  // namespace wardmap::semantics
