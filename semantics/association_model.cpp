#include "semantics/association_model.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace wardmap::semantics {

namespace {

constexpr double kNegInf = -std::numeric_limits<double>::infinity();

hdp::GaussianMixtureOptions gmm_options(const AssociationOptions& o) {
  hdp::GaussianMixtureOptions g;
  g.sigma_per_dim.resize(6);
  g.sigma_per_dim << o.sigma_position, o.sigma_position, o.sigma_position, o.sigma_rotation, o.sigma_rotation,
      o.sigma_rotation;
  return g;
}

bool share_measurement(const GroupObject& a, const GroupObject& b) {
  auto i = a.measurements.begin(), j = b.measurements.begin();
  while (i != a.measurements.end() && j != b.measurements.end()) {
    if (*i < *j) ++i;
    else if (*j < *i) ++j;
    else return true;
  }
  return false;
}

}  // namespace

Eigen::VectorXd pose_feature(const ObjectPose& pose) {
  Eigen::VectorXd f(6);
  f.head<3>() = pose.pose.translation();
  f.tail<3>() = slam::so3_log(pose.pose.rotation_matrix());
  return f;
}

AssociationModel::AssociationModel(const std::vector<GroupObject>& objects, const std::vector<std::vector<int>>& groups,
                                   const AssociationOptions& options)
    : objects_(objects), groups_(groups), options_(options) {
  const auto g = gmm_options(options);
  gmms_.reserve(objects.size());
  for (const auto& o : objects) gmms_.push_back(hdp::GaussianMixture::from_measurements(o.features, g));
  // A single component evaluated new_landmark_distance away along one position axis.
  Eigen::VectorXd zero = Eigen::VectorXd::Zero(6), at = zero;
  at(0) = options.new_landmark_distance;
  log_new_ = hdp::GaussianMixture::from_measurements({zero}, g).log_density(at);
}

// Assoc. III-A.2: max GMM probability of the item's measurements under the member's GMM, x1.5 when
// they share measurements in overlapping keyframes.
double AssociationModel::log_prior(int item_object, int member_object) const {
  const GroupObject& a = objects_[item_object];
  const GroupObject& b = objects_[member_object];
  double lp = log_new_;
  if (!a.features.empty() && !gmms_[member_object].empty()) lp = gmms_[member_object].max_log_density(a.features);
  if (share_measurement(a, b)) lp += std::log(options_.overlap_boost);
  return lp;
}

double AssociationModel::appearance_term(const Eigen::VectorXf& a, const Eigen::VectorXf& b) const {
  if (a.size() == 0 || b.size() == 0 || a.size() != b.size()) return 0.0;
  return options_.appearance_weight * (static_cast<double>(a.dot(b)) - options_.appearance_neutral);
}

double AssociationModel::log_predictive(const hdp::ItemRef& item, const std::vector<hdp::ItemRef>& members) const {
  const int io = groups_[item.group][item.item];
  const GroupObject& obj = objects_[io];
  double best = kNegInf;
  bool shares = false;
  Eigen::VectorXf mean_embedding;
  for (const auto& m : members) {
    const int mo = groups_[m.group][m.item];
    if (objects_[mo].label != obj.label) return kNegInf;  // class: landmarks hold one class
    if (!options_.landmark_mixture) best = std::max(best, log_prior(io, mo));
    else shares = shares || share_measurement(obj, objects_[mo]);  // the mixture's overlap boost
    const auto& e = objects_[mo].embedding;
    if (e.size() > 0) mean_embedding = mean_embedding.size() ? Eigen::VectorXf(mean_embedding + e) : e;
  }
  if (options_.landmark_mixture) best = log_mixture_prior(io, members) + (shares ? std::log(options_.overlap_boost) : 0.0);
  if (mean_embedding.size() > 0 && mean_embedding.norm() > 0) mean_embedding.normalize();
  return best + appearance_term(obj.embedding, mean_embedding);
}

// Assoc. III-A.2 with the landmark's GMM taken as the equal-weight mixture of its group objects'
// GMMs: the largest probability of the item's measurements under it. One stray member (a group
// object with a measurement on its neighbour) then weighs 1/N, and cannot chain two objects.
double AssociationModel::log_mixture_prior(int item_object, const std::vector<hdp::ItemRef>& members) const {
  const GroupObject& a = objects_[item_object];
  if (a.features.empty()) return log_new_;
  std::vector<int> placed;
  for (const auto& m : members) {
    const int mo = groups_[m.group][m.item];
    if (!gmms_[mo].empty()) placed.push_back(mo);
  }
  if (placed.empty()) return log_new_;
  double best = kNegInf;
  std::vector<double> logs(placed.size());
  for (const auto& x : a.features) {
    for (size_t k = 0; k < placed.size(); ++k) logs[k] = gmms_[placed[k]].log_density(x);
    const double top = *std::max_element(logs.begin(), logs.end());
    if (top == kNegInf) continue;
    double sum = 0;
    for (double l : logs) sum += std::exp(l - top);
    best = std::max(best, top + std::log(sum / placed.size()));
  }
  return best;
}

// A landmark is one object in one place: the spread of its group objects' mean positions about
// their mean, as Gaussians of sigma_position (unnormalised), weighted by compactness_weight. Two
// half-landmarks (early views of one chair, late views of its neighbour) then score badly.
double AssociationModel::log_marginal(const std::vector<hdp::ItemRef>& members) const {
  double lm = hdp::CrfModel::log_marginal(members);
  if (options_.compactness_weight <= 0) return lm;
  std::vector<Eigen::Vector3d> means;
  Eigen::Vector3d c = Eigen::Vector3d::Zero();
  for (const auto& m : members) {
    const GroupObject& b = object(m);
    if (b.features.empty()) continue;
    Eigen::Vector3d mean = Eigen::Vector3d::Zero();
    for (const auto& f : b.features) mean += f.head<3>();
    means.push_back(mean / b.features.size());
    c += means.back();
  }
  if (means.size() < 2) return lm;
  c /= means.size();
  double ss = 0;
  for (const auto& m : means) ss += (m - c).squaredNorm();
  return lm - options_.compactness_weight * 0.5 * ss / (options_.sigma_position * options_.sigma_position);
}

double AssociationModel::log_predictive_new(const hdp::ItemRef&) const { return log_new_; }

std::vector<std::pair<int, int>> keyframe_measurements_of(const std::vector<int>& ids,
                                                          const std::vector<ObjectMeasurement>& ms) {
  std::vector<std::pair<int, int>> out;
  out.reserve(ids.size());
  for (int id : ids) out.emplace_back(ms[id].keyframe, id);
  std::sort(out.begin(), out.end());
  return out;
}

int keyframes_detected_apart(const std::vector<std::pair<int, int>>& a, const std::vector<std::pair<int, int>>& b,
                             int stop_at) {
  // Walk both sorted lists per keyframe.
  int n = 0;
  auto i = a.begin(), j = b.begin();
  while (i != a.end() && j != b.end() && n < stop_at) {
    if (i->first < j->first) {
      ++i;
    } else if (j->first < i->first) {
      ++j;
    } else if (i->second != j->second) {  // counted once per keyframe
      if (++n >= stop_at) break;
      const int kf = i->first;
      while (i != a.end() && i->first == kf) ++i;
      while (j != b.end() && j->first == kf) ++j;
    } else {
      ++i, ++j;
    }
  }
  return n;
}

bool detected_apart_in_share(const std::vector<std::pair<int, int>>& a, const std::vector<std::pair<int, int>>& b,
                             double min_share) {
  const auto keyframes = [](const std::vector<std::pair<int, int>>& k) {  // sorted by keyframe
    int n = 0;
    for (size_t i = 0; i < k.size(); ++i) n += i == 0 || k[i].first != k[i - 1].first;
    return n;
  };
  const int fewer = std::min(keyframes(a), keyframes(b));
  return fewer > 0 && keyframes_detected_apart(a, b) >= min_share * fewer;
}

bool detected_apart_in_one_keyframe(const std::vector<std::pair<int, int>>& a,
                                    const std::vector<std::pair<int, int>>& b) {
  return keyframes_detected_apart(a, b, 1) > 0;
}

bool AssociationModel::cannot_link(const hdp::ItemRef& a, const hdp::ItemRef& b) const {
  const GroupObject& x = object(a);
  const GroupObject& y = object(b);
  return x.label != y.label || detected_apart_in_one_keyframe(x.keyframe_measurements, y.keyframe_measurements);
}

}  // namespace wardmap::semantics
