#include "slam/front/local_bundle_adjustment.h"

#include <algorithm>
#include <array>
#include <map>
#include <memory>
#include <unordered_map>
#include <unordered_set>

#include "slam/front/pose_optimizer.h"
#include "slam/front/reprojection_costs.h"
#include "slam/front/submap.h"

namespace wardmap::slam {

namespace {

struct BAObservation {
  KeyFrame* keyframe;
  MapPoint* point;
  int index;
};

// Ends a solve, keeping its current state, once `abort` says so.
class AbortCallback : public ceres::IterationCallback {
 public:
  AbortCallback(const std::function<bool()>& abort, bool& aborted) : abort_(abort), aborted_(aborted) {}
  ceres::CallbackReturnType operator()(const ceres::IterationSummary&) override {
    if (!abort_ || !abort_()) return ceres::SOLVER_CONTINUE;
    aborted_ = true;
    return ceres::SOLVER_TERMINATE_SUCCESSFULLY;
  }

 private:
  const std::function<bool()>& abort_;
  bool& aborted_;
};

}  // namespace

LocalBAResult local_bundle_adjustment(const std::shared_ptr<KeyFrame>& keyframe, Submap& submap,
                                      const PinholeCamera& camera, const FrontOptions& options,
                                      std::unique_lock<std::mutex>* lock, const std::function<bool()>& abort) {
  LocalBAResult result;
  const MappingOptions& m = options.mapping;
  // Local keyframes and points.
  const int max_keyframes = options.monocular ? m.ba_max_keyframes_mono : m.ba_max_keyframes;
  const int max_fixed = options.monocular ? m.ba_max_fixed_keyframes_mono : m.ba_max_fixed_keyframes;
  std::vector<std::shared_ptr<KeyFrame>> local = keyframe->best_covisibles(max_keyframes - 1);
  local.insert(local.begin(), keyframe);
  std::unordered_set<KeyFrameId> local_ids;
  for (const auto& kf : local) local_ids.insert(kf->id());
  std::vector<std::shared_ptr<MapPoint>> points;
  std::unordered_set<MapPointId> point_ids;
  for (const auto& kf : local)
    for (const auto& mp : kf->map_points())
      if (mp && !mp->bad() && point_ids.insert(mp->id()).second) points.push_back(mp);
  // Fixed keyframes: the others that see local points, those sharing most points first.
  std::map<KeyFrameId, std::pair<std::shared_ptr<KeyFrame>, int>> others;
  for (const auto& mp : points)
    for (const auto& [id, obs] : mp->observations())
      if (!local_ids.count(id))
        if (auto kf = obs.keyframe.lock(); kf && !kf->bad()) {
          auto& o = others[id];
          o.first = kf;
          ++o.second;
        }
  std::vector<std::pair<int, std::shared_ptr<KeyFrame>>> ranked;
  for (auto& [id, o] : others) ranked.emplace_back(o.second, o.first);
  std::stable_sort(ranked.begin(), ranked.end(), [](const auto& a, const auto& b) { return a.first > b.first; });
  std::map<KeyFrameId, std::shared_ptr<KeyFrame>> fixed;
  for (const auto& [n, kf] : ranked) {
    if (static_cast<int>(fixed.size()) >= max_fixed) break;
    fixed[kf->id()] = kf;
  }

  // Parameter blocks live in contiguous vectors filled in a fixed order: Ceres sorts the blocks of
  // an elimination group by address, so blocks scattered over the heap would be eliminated in an
  // order that changes from run to run (last digits of --deterministic output, seen under ASan).
  std::vector<std::array<double, 7>> pose_blocks;  // qx qy qz qw tx ty tz
  std::map<KeyFrameId, size_t> pose_index;
  auto add_pose = [&](const std::shared_ptr<KeyFrame>& kf) {
    const Eigen::Quaterniond q = kf->pose_cw().rotation().normalized();
    const Eigen::Vector3d& t = kf->pose_cw().translation();
    pose_index[kf->id()] = pose_blocks.size();
    pose_blocks.push_back({q.x(), q.y(), q.z(), q.w(), t.x(), t.y(), t.z()});
  };
  for (const auto& kf : local) add_pose(kf);
  for (const auto& [id, kf] : fixed) add_pose(kf);
  std::vector<std::array<double, 3>> position_blocks;
  std::unordered_map<MapPointId, size_t> position_index;
  std::vector<BAObservation> observations;
  for (const auto& mp : points) {
    int n = 0;
    for (const auto& [id, obs] : mp->observations())
      if (pose_index.count(id)) ++n;
    if (n < 2) continue;  // a point seen once is not constrained (docs/TOOLCHAIN.md)
    position_index[mp->id()] = position_blocks.size();
    position_blocks.push_back({mp->position().x(), mp->position().y(), mp->position().z()});
    for (const auto& [id, obs] : mp->observations())
      if (pose_index.count(id))
        if (auto kf = obs.keyframe.lock(); kf && !kf->bad()) observations.push_back({kf.get(), mp.get(), obs.index});
  }
  if (observations.empty()) return result;

  // The gauge: the origin and the fixed keyframes; with none of them, the oldest local keyframe.
  std::unordered_set<KeyFrameId> constant;
  for (const auto& [id, kf] : fixed) constant.insert(id);
  if (submap.origin()) constant.insert(submap.origin()->id());
  bool any_fixed = false;
  for (const auto& [id, i] : pose_index) any_fixed |= constant.count(id) > 0;
  if (!any_fixed) constant.insert(pose_index.begin()->first);

  const PinholeIntrinsics K{camera.fx, camera.fy, camera.cx, camera.cy, keyframe->features().bf};
  std::vector<char> inlier(observations.size(), 1);

  // One cost function per observation, shared by both solves (the problems do not own them).
  std::vector<std::unique_ptr<ceres::CostFunction>> costs(observations.size());
  // One Huber loss per kind of observation, shared by its residual blocks (a loss holds only its
  // threshold), instead of one allocated and freed per observation and solve.
  ceres::HuberLoss huber_mono(std::sqrt(options.tracking.chi2_mono));
  ceres::HuberLoss huber_stereo(std::sqrt(options.tracking.chi2_stereo));
  auto solve = [&](bool robust, int iterations) {
    ceres::Problem::Options po;
    po.manifold_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
    po.cost_function_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
    po.loss_function_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
    po.disable_all_safety_checks = true;  // the blocks are ours and valid; saves time building
    ceres::Problem problem(po);
    ceres::ProductManifold<ceres::EigenQuaternionManifold, ceres::EuclideanManifold<3>> pose_manifold;
    auto* ordering = new ceres::ParameterBlockOrdering;
    for (size_t i = 0; i < observations.size(); ++i) {
      if (!inlier[i]) continue;
      const BAObservation& o = observations[i];
      const bool stereo = costs[i]->num_residuals() == 3;
      ceres::LossFunction* loss = robust ? (stereo ? &huber_stereo : &huber_mono) : nullptr;
      double* pose = pose_blocks[pose_index.at(o.keyframe->id())].data();
      double* point = position_blocks[position_index.at(o.point->id())].data();
      problem.AddResidualBlock(costs[i].get(), loss, pose, point);
    }
    for (auto& x : position_blocks)
      if (problem.HasParameterBlock(x.data())) ordering->AddElementToGroup(x.data(), 0);
    for (const auto& [id, i] : pose_index) {
      auto& p = pose_blocks[i];
      if (!problem.HasParameterBlock(p.data())) continue;
      ordering->AddElementToGroup(p.data(), 1);
      problem.SetManifold(p.data(), &pose_manifold);
      if (constant.count(id)) problem.SetParameterBlockConstant(p.data());
    }
    ceres::Solver::Options so;
    so.linear_solver_type = ceres::DENSE_SCHUR;
    so.linear_solver_ordering.reset(ordering);
    so.jacobi_scaling = false;
    so.max_num_iterations = iterations;
    so.logging_type = ceres::SILENT;
    so.num_threads = 1;
    AbortCallback stop(abort, result.aborted);
    if (abort) so.callbacks.push_back(&stop);
    ceres::Solver::Summary summary;
    ceres::Solve(so, &problem, &summary);
    if (result.initial_cost == 0) result.initial_cost = summary.initial_cost;
    result.final_cost = summary.final_cost;
  };

  auto pose_of = [&](KeyFrameId id) {
    const auto& p = pose_blocks[pose_index.at(id)];
    return SE3(Eigen::Quaterniond(p[3], p[0], p[1], p[2]).normalized(), Eigen::Vector3d(p[4], p[5], p[6]));
  };
  auto classify = [&]() {
    int outliers = 0;
    for (size_t i = 0; i < observations.size(); ++i) {
      const BAObservation& o = observations[i];
      const FrameFeatures& f = o.keyframe->features();
      const size_t k = static_cast<size_t>(o.index);
      const auto& x = position_blocks[position_index.at(o.point->id())];
      PoseObservation po{Eigen::Vector3d(x[0], x[1], x[2]), f.points[k], f.right_u[k],
                         f.pyramid->inv_scale[static_cast<size_t>(f.levels[k])]};
      const double chi2 = observation_chi2(pose_of(o.keyframe->id()), po, camera, K.bf);
      const double th = po.right_u >= 0 ? options.tracking.chi2_stereo : options.tracking.chi2_mono;
      inlier[i] = chi2 <= th ? 1 : 0;
      outliers += inlier[i] ? 0 : 1;
    }
    return outliers;
  };

  // From here to the write-back only copies and the (immutable) keyframe features are read.
  if (lock) lock->unlock();
  for (size_t i = 0; i < observations.size(); ++i) {
    const BAObservation& o = observations[i];
    const FrameFeatures& f = o.keyframe->features();
    const size_t k = static_cast<size_t>(o.index);
    const double inv_sigma = f.pyramid->inv_scale[static_cast<size_t>(f.levels[k])];
    if (f.right_u[k] >= 0)
      costs[i] = std::make_unique<BundleReprojectionCost<3>>(K, f.points[k], f.right_u[k], inv_sigma);
    else
      costs[i] = std::make_unique<BundleReprojectionCost<2>>(K, f.points[k], -1, inv_sigma);
  }
  if (m.ba_iterations_robust > 0) solve(true, m.ba_iterations_robust);
  classify();
  if (m.ba_iterations_refine > 0 && !result.aborted) solve(false, m.ba_iterations_refine);
  result.outliers = classify();
  if (lock) lock->lock();

  // Write back.
  for (const auto& kf : local)
    if (!constant.count(kf->id()) && !kf->bad()) kf->set_pose_cw(pose_of(kf->id()));
  for (size_t i = 0; i < observations.size(); ++i) {
    if (inlier[i]) continue;
    const BAObservation& o = observations[i];
    if (o.keyframe->map_point(static_cast<size_t>(o.index)).get() == o.point) o.keyframe->erase_map_point(o.index);
    o.point->erase_observation(o.keyframe->id());
  }
  for (const auto& mp : points) {
    auto it = position_index.find(mp->id());
    if (it == position_index.end() || mp->bad()) continue;
    const auto& x = position_blocks[it->second];
    mp->set_position(Eigen::Vector3d(x[0], x[1], x[2]));
    mp->update_normal_and_depth();
  }
  submap.purge_bad_points(points);  // outlier observations may have left a point with none
  result.keyframes = static_cast<int>(local.size());
  result.fixed_keyframes = static_cast<int>(fixed.size());
  result.points = static_cast<int>(position_blocks.size());
  result.observations = static_cast<int>(observations.size());
  return result;
}

}  // namespace wardmap::slam
