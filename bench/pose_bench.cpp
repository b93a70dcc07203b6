// Pose-only optimisation per call (ORB-SLAM's PoseOptimization: 4 rounds, Huber in the first 2) on
// synthetic observations of a tracked frame, every tenth one an outlier: the Ceres solver (the
// default) against wardmap's own Levenberg-Marquardt (`tracking.pose_solver: lm`). The tracker
// calls it about twice per frame (motion model, then local map).
#include <benchmark/benchmark.h>

#include <cmath>
#include <random>
#include <vector>

#include "slam/front/pose_optimizer.h"

namespace wardmap::bench {
namespace {

struct PoseProblem {
  slam::PinholeCamera camera;
  slam::SE3 initial;
  std::vector<slam::PoseObservation> observations;
};

// n observations of points 1.5-6 m in front of a 640x480 camera (fx 525), 0.5 px noise, the image
// pyramid's level scales, and a pose to start from a few centimetres and a degree off.
PoseProblem make_problem(int n, bool stereo, double bf) {
  PoseProblem p;
  p.camera.fx = p.camera.fy = 525;
  p.camera.cx = 319.5, p.camera.cy = 239.5;
  p.camera.width = 640, p.camera.height = 480;
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> ux(-2, 2), uy(-1.5, 1.5), uz(1.5, 6);
  std::normal_distribution<double> noise(0, 0.5);
  std::uniform_int_distribution<int> level(0, 7);
  const slam::SE3 truth = slam::SE3::exp((slam::Vector6d() << 0.1, -0.05, 0.2, 0.02, -0.03, 0.01).finished());
  while (static_cast<int>(p.observations.size()) < n) {
    const Eigen::Vector3d pc(ux(rng), uy(rng), uz(rng));
    const Eigen::Vector2d px(p.camera.fx * pc.x() / pc.z() + p.camera.cx, p.camera.fy * pc.y() / pc.z() + p.camera.cy);
    if (!p.camera.in_image(px)) continue;
    slam::PoseObservation o;
    o.point = truth.inverse() * pc;
    const bool outlier = p.observations.size() % 10 == 0;
    o.pixel = px + Eigen::Vector2d(noise(rng), noise(rng)) + (outlier ? Eigen::Vector2d(25, -30) : Eigen::Vector2d::Zero());
    if (stereo) o.right_u = px.x() - bf / pc.z() + noise(rng);
    o.inv_sigma = 1.0 / std::pow(1.2, level(rng));
    p.observations.push_back(o);
  }
  p.initial = truth * slam::SE3::exp((slam::Vector6d() << 0.03, 0.02, -0.04, 0.01, 0.01, -0.01).finished());
  return p;
}

// Args: observations, solver (0 Ceres, 1 lm), stereo (RGB-D's virtual right coordinate).
void BM_PoseOptimize(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  const bool stereo = state.range(2) != 0;
  const double bf = 0.2 * 525;
  const PoseProblem p = make_problem(n, stereo, bf);
  slam::PoseOptimizerOptions options;
  options.solver = state.range(1) ? slam::PoseSolver::kLevenbergMarquardt : slam::PoseSolver::kCeres;
  int inliers = 0;
  for (auto _ : state) {
    const slam::PoseEstimate est = slam::optimize_pose(p.initial, p.observations, p.camera, bf, options);
    benchmark::DoNotOptimize(est.T_cw);
    inliers = est.inliers;
  }
  state.counters["inliers"] = inliers;
}
BENCHMARK(BM_PoseOptimize)
    ->ArgNames({"obs", "lm", "stereo"})
    ->ArgsProduct({{150, 400}, {0, 1}, {0, 1}})
    ->Unit(benchmark::kMicrosecond)
    ->MinTime(0.5);

}  // namespace
}  // namespace wardmap::bench
