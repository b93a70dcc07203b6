#include "slam/front/pose_optimizer.h"

#include <gtest/gtest.h>

#include "slam/front/reprojection_costs.h"
#include "tests/support/pose_scene.h"
#include "tests/support/test_camera.h"

namespace wardmap::slam {

namespace {
PinholeCamera camera() { return test::vga_camera(525); }

using Scene = test::PoseScene;

Scene make_scene(const PinholeCamera& cam, double bf, const SE3& truth, bool stereo) {
  return test::make_pose_scene(cam, bf, truth, stereo);
}

}  // namespace

class PoseOptimizerTest : public ::testing::TestWithParam<std::tuple<bool, PoseSolver>> {};

TEST_P(PoseOptimizerTest, RecoversAPerturbedPoseAndFlagsOutliers) {
  const bool stereo = std::get<0>(GetParam());
  const PinholeCamera cam = camera();
  const double bf = 0.08 * cam.fx;
  const SE3 truth = SE3::exp((Vector6d() << 0.1, -0.05, 0.2, 0.02, -0.03, 0.01).finished());
  const Scene scene = make_scene(cam, bf, truth, stereo);
  const auto& obs = scene.obs;
  const auto& is_outlier = scene.is_outlier;
  const SE3 initial = truth * SE3::exp((Vector6d() << 0.05, 0.03, -0.06, 0.02, 0.015, -0.02).finished());
  PoseOptimizerOptions options;
  options.solver = std::get<1>(GetParam());
  const PoseEstimate est = optimize_pose(initial, obs, cam, bf, options);
  const SE3 err = est.T_cw * truth.inverse();
  EXPECT_LT(err.translation().norm(), 5e-3);
  EXPECT_LT(rotation_angle(err.rotation()), 1e-3);
  int flagged = 0, wrong = 0;
  for (size_t i = 0; i < obs.size(); ++i) {
    if (is_outlier[i]) flagged += est.inlier[i] ? 0 : 1;
    if (!is_outlier[i] && !est.inlier[i]) ++wrong;
  }
  EXPECT_EQ(flagged, 30);
  EXPECT_LT(wrong, 15);  // the chi2 test at 95 % rejects ~5 % of good observations
  EXPECT_EQ(est.inliers, static_cast<int>(std::count(est.inlier.begin(), est.inlier.end(), 1)));
}

INSTANTIATE_TEST_SUITE_P(MonoAndStereo, PoseOptimizerTest,
                         ::testing::Combine(::testing::Values(false, true),
                                            ::testing::Values(PoseSolver::kLevenbergMarquardt, PoseSolver::kCeres)));

// The own Levenberg-Marquardt and Ceres minimise the same cost: same pose (to well below the noise)
// and the same outlier decisions, from a start far enough for the Huber loss to matter.
TEST(PoseOptimizer, LevenbergMarquardtAgreesWithCeres) {
  for (const bool stereo : {false, true}) {
    const PinholeCamera cam = camera();
    const double bf = 0.08 * cam.fx;
    const SE3 truth = SE3::exp((Vector6d() << -0.2, 0.1, 0.05, -0.01, 0.04, 0.02).finished());
    const Scene scene = make_scene(cam, bf, truth, stereo);
    const SE3 initial = truth * SE3::exp((Vector6d() << -0.08, 0.05, 0.1, 0.03, -0.02, 0.03).finished());
    PoseOptimizerOptions lm, ceres_options;
    lm.solver = PoseSolver::kLevenbergMarquardt;
    ceres_options.solver = PoseSolver::kCeres;
    const PoseEstimate a = optimize_pose(initial, scene.obs, cam, bf, lm);
    const PoseEstimate b = optimize_pose(initial, scene.obs, cam, bf, ceres_options);
    const SE3 d = a.T_cw * b.T_cw.inverse();
    EXPECT_LT(d.translation().norm(), 1e-5) << stereo;
    EXPECT_LT(rotation_angle(d.rotation()), 1e-6) << stereo;
    EXPECT_EQ(a.inlier, b.inlier) << stereo;
  }
}

// optimize_pose's Ceres round puts all observations into one residual block, each with its own Huber
// loss; it must take the steps of the textbook problem, one block and one ceres::HuberLoss per
// observation (this test's reference), from a start far enough for the loss to matter.
TEST(PoseOptimizer, CeresRoundEqualsOneBlockPerObservation) {
  for (const bool stereo : {false, true}) {
    for (const bool robust : {true, false}) {
      const PinholeCamera cam = camera();
      const double bf = 0.08 * cam.fx;
      const SE3 truth = SE3::exp((Vector6d() << 0.15, -0.1, 0.05, 0.03, 0.02, -0.04).finished());
      const Scene scene = make_scene(cam, bf, truth, stereo);
      const SE3 initial = truth * SE3::exp((Vector6d() << 0.07, -0.06, 0.09, -0.03, 0.02, 0.025).finished());
      PoseOptimizerOptions options;
      options.solver = PoseSolver::kCeres;
      options.rounds = 1;
      options.robust_rounds = robust ? 1 : 0;
      const PoseEstimate est = optimize_pose(initial, scene.obs, cam, bf, options);

      const PinholeIntrinsics K{cam.fx, cam.fy, cam.cx, cam.cy, bf};
      double delta[6] = {0, 0, 0, 0, 0, 0};
      ceres::Problem problem;
      for (const PoseObservation& o : scene.obs) {
        const bool s = o.right_u >= 0;
        ceres::CostFunction* cost = s ? static_cast<ceres::CostFunction*>(new PosePerturbationCost<3>(K, initial, o))
                                      : new PosePerturbationCost<2>(K, initial, o);
        ceres::LossFunction* loss =
            robust ? new ceres::HuberLoss(std::sqrt(s ? options.chi2_stereo : options.chi2_mono)) : nullptr;
        problem.AddResidualBlock(cost, loss, delta);
      }
      ceres::Solver::Options so;
      so.linear_solver_type = ceres::DENSE_NORMAL_CHOLESKY;
      so.max_num_iterations = options.iterations;
      so.logging_type = ceres::SILENT;
      ceres::Solver::Summary summary;
      ceres::Solve(so, &problem, &summary);
      const SE3 reference = SE3::exp(Eigen::Map<const Vector6d>(delta)) * initial;

      const SE3 d = est.T_cw * reference.inverse();
      EXPECT_LT(d.translation().norm(), 1e-12) << stereo << robust;
      EXPECT_LT(rotation_angle(d.rotation()), 1e-12) << stereo << robust;
      // The reference moved: the comparison is not between two untouched starts.
      EXPECT_GT((reference * initial.inverse()).translation().norm(), 0.01);
    }
  }
}

// A point behind the camera at the start neither stops the solve nor counts as an inlier.
TEST(PoseOptimizer, PointsBehindTheCameraAreOutliers) {
  const PinholeCamera cam = camera();
  const SE3 truth;
  Scene scene = make_scene(cam, 0, truth, false);
  scene.obs[5].point = Eigen::Vector3d(0.1, 0.2, -2.0);
  const SE3 initial = SE3::exp((Vector6d() << 0.02, -0.01, 0.03, 0.01, 0.0, -0.01).finished());
  const PoseEstimate est = optimize_pose(initial, scene.obs, cam, 0, PoseOptimizerOptions{});
  EXPECT_FALSE(est.inlier[5]);
  EXPECT_LT(est.T_cw.translation().norm(), 5e-3);
}

TEST(PoseOptimizer, ChiSquareIsInfiniteBehindTheCamera) {
  PoseObservation o;
  o.point = Eigen::Vector3d(0, 0, -1);
  o.pixel = Eigen::Vector2d(320, 240);
  EXPECT_TRUE(std::isinf(observation_chi2(SE3(), o, camera(), 40)));
}

}  // namespace wardmap::slam
