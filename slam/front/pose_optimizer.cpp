#include "slam/front/pose_optimizer.h"

#include <limits>

#include "slam/front/reprojection_costs.h"

namespace wardmap::slam {


double observation_chi2(const SE3& T_cw, const PoseObservation& o, const PinholeCamera& c, double bf) {
  const Eigen::Vector3d pc = T_cw * o.point;
  if (pc.z() <= 1e-6) return std::numeric_limits<double>::infinity();
  const double u = c.fx * pc.x() / pc.z() + c.cx;
  const double v = c.fy * pc.y() / pc.z() + c.cy;
  double e2 = (u - o.pixel.x()) * (u - o.pixel.x()) + (v - o.pixel.y()) * (v - o.pixel.y());
  if (o.right_u >= 0) {
    const double er = u - bf / pc.z() - o.right_u;
    e2 += er * er;
  }
  return e2 * o.inv_sigma * o.inv_sigma;
}

PoseEstimate optimize_pose(const SE3& initial, const std::vector<PoseObservation>& obs, const PinholeCamera& camera,
                           double bf, const PoseOptimizerOptions& options) {
  PoseEstimate est;
  est.T_cw = initial;
  est.inlier.assign(obs.size(), 1);
  est.inliers = static_cast<int>(obs.size());
  if (obs.size() < 3) return est;
  const PinholeIntrinsics K{camera.fx, camera.fy, camera.cx, camera.cy, bf};

  for (int round = 0; round < options.rounds; ++round) {
    double delta[6] = {0, 0, 0, 0, 0, 0};
    PerturbationCache cache;
    ceres::Problem problem;
    problem.AddParameterBlock(delta, 6);
    const bool robust = round < options.robust_rounds;
    int used = 0;
    for (size_t i = 0; i < obs.size(); ++i) {
      if (!est.inlier[i]) continue;
      const PoseObservation& o = obs[i];
      const bool stereo = o.right_u >= 0;
      ceres::CostFunction* cost =
          stereo ? static_cast<ceres::CostFunction*>(new PosePerturbationCost<3>(K, est.T_cw, o, &cache))
                 : new PosePerturbationCost<2>(K, est.T_cw, o, &cache);
      ceres::LossFunction* loss =
          robust ? new ceres::HuberLoss(std::sqrt(stereo ? options.chi2_stereo : options.chi2_mono)) : nullptr;
      problem.AddResidualBlock(cost, loss, delta);
      ++used;
    }
    if (used < 3) break;
    ceres::Solver::Options so;
    so.linear_solver_type = ceres::DENSE_NORMAL_CHOLESKY;
    so.max_num_iterations = options.iterations;
    so.logging_type = ceres::SILENT;
    so.num_threads = 1;
    ceres::Solver::Summary summary;
    ceres::Solve(so, &problem, &summary);
    Vector6d d;
    for (int i = 0; i < 6; ++i) d[i] = delta[i];
    est.T_cw = SE3::exp(d) * est.T_cw;

    est.inliers = 0;
    for (size_t i = 0; i < obs.size(); ++i) {
      const double chi2 = observation_chi2(est.T_cw, obs[i], camera, bf);
      const double th = obs[i].right_u >= 0 ? options.chi2_stereo : options.chi2_mono;
      est.inlier[i] = chi2 <= th ? 1 : 0;
      est.inliers += est.inlier[i];
    }
    if (est.inliers < 10) break;
  }
  return est;
}

}  // namespace wardmap::slam
