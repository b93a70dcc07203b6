// Pose-only optimisation per call (ORB-SLAM's PoseOptimization: 4 rounds, Huber in the first 2) on
// synthetic observations of a tracked frame, every tenth one an outlier: the Ceres solver (the
// default) against wardmap's own Levenberg-Marquardt (`tracking.pose_solver: lm`). The tracker
// calls it about twice per frame (motion model, then local map).
#include <benchmark/benchmark.h>

#include "slam/front/pose_optimizer.h"
#include "tests/support/pose_scene.h"
#include "tests/support/test_camera.h"

namespace wardmap::bench {
namespace {

// Args: observations, solver (0 Ceres, 1 lm), stereo (RGB-D's virtual right coordinate).
void BM_PoseOptimize(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  const bool stereo = state.range(2) != 0;
  const double bf = 0.2 * 525;
  // 640x480, fx 525; the start a few centimetres and a degree off the truth.
  const slam::PinholeCamera camera = test::vga_camera(525);
  const slam::SE3 truth = slam::SE3::exp((slam::Vector6d() << 0.1, -0.05, 0.2, 0.02, -0.03, 0.01).finished());
  const slam::SE3 initial = truth * slam::SE3::exp((slam::Vector6d() << 0.03, 0.02, -0.04, 0.01, 0.01, -0.01).finished());
  const test::PoseScene scene = test::make_pose_scene(camera, bf, truth, stereo, n, 7, /*pyramid_levels=*/true);
  slam::PoseOptimizerOptions options;
  options.solver = state.range(1) ? slam::PoseSolver::kLevenbergMarquardt : slam::PoseSolver::kCeres;
  int inliers = 0;
  for (auto _ : state) {
    const slam::PoseEstimate est = slam::optimize_pose(initial, scene.obs, camera, bf, options);
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
