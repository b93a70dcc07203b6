#include "slam/eval/trajectory_eval.h"

#include <gtest/gtest.h>

#include <random>

#include <opencv2/core.hpp>

#include "slam/eval/trajectory_plot.h"
#include "tests/support/test_support.h"

namespace wardmap::slam::eval {
namespace {

Trajectory circle(int n, double rate, double t0 = 0) {
  Trajectory t;
  for (int i = 0; i < n; ++i) {
    const double a = 0.05 * i;
    t.push_back(t0 + i / rate, SE3(Eigen::Quaterniond(Eigen::AngleAxisd(a, Eigen::Vector3d::UnitY())),
                                   Eigen::Vector3d(3 * std::cos(a), 0.2 * std::sin(3 * a), 3 * std::sin(a))));
  }
  return t;
}

TEST(Associate, ClosestWithinWindowEachUsedOnce) {
  Trajectory gt = circle(100, 100.0);  // 100 Hz ground truth
  Trajectory est;
  for (int i = 0; i < 30; ++i) est.push_back(i / 30.0 + 0.003, gt.poses[0]);
  const auto pairs = associate(gt, est, {});
  ASSERT_EQ(pairs.size(), 30u);
  for (const auto& [g, e] : pairs) EXPECT_LE(std::abs(gt.timestamps[g] - est.timestamps[e]), 0.02);
  Trajectory far = est;
  for (auto& t : far.timestamps) t += 5;  // beyond the ground truth
  EXPECT_TRUE(associate(gt, far, {}).empty());
}

TEST(Ate, ZeroForTransformedCopyUnderSim3ButNotUnderSe3) {
  const Trajectory gt = circle(60, 30);
  const Sim3 S(0.37, Eigen::Quaterniond(Eigen::AngleAxisd(1.1, Eigen::Vector3d(1, 0, 1).normalized())), Eigen::Vector3d(4, -2, 1));
  Trajectory est = gt;
  for (auto& p : est.poses) p = S.transform_pose(p);
  const auto pairs = associate(gt, est, {});
  const AteResult sim = compute_ate(gt, est, pairs, Alignment::Sim3);
  EXPECT_LT(sim.stats.rmse, 1e-9);
  EXPECT_NEAR(sim.scale, 1 / 0.37, 1e-9);
  EXPECT_GT(compute_ate(gt, est, pairs, Alignment::SE3).stats.rmse, 0.5);
  const AteResult none = compute_ate(gt, gt, pairs, Alignment::None);
  EXPECT_EQ(none.stats.rmse, 0.0);
}

TEST(Ate, StatisticsOfKnownErrors) {
  const ErrorStats s = error_stats({3, 1, 2, 4});
  EXPECT_DOUBLE_EQ(s.mean, 2.5);
  EXPECT_DOUBLE_EQ(s.median, 2.5);
  EXPECT_DOUBLE_EQ(s.max, 4);
  EXPECT_DOUBLE_EQ(s.rmse, std::sqrt(30.0 / 4));
}

TEST(Rpe, ZeroForRigidCopyAndScaleAware) {
  const Trajectory gt = circle(50, 30);
  Trajectory est = gt;
  const Sim3 S(2.0, Eigen::Quaterniond(Eigen::AngleAxisd(0.4, Eigen::Vector3d::UnitZ())), Eigen::Vector3d(1, 1, 1));
  for (auto& p : est.poses) p = S.transform_pose(p);
  const auto pairs = associate(gt, est, {});
  const RpeResult r = compute_rpe(gt, est, pairs, 5, 0.5);
  EXPECT_EQ(r.count, 45u);
  EXPECT_LT(r.translation.rmse, 1e-9);
  EXPECT_LT(r.rotation_deg.rmse, 1e-6);
}

// A walk along x at 1 m/s, 30 Hz, 20 s, standing still for the first `rest` seconds; the estimate's
// speed is `scale(t)` times the truth's, in a rotated frame.
template <typename Scale>
std::pair<Trajectory, Trajectory> walk(Scale scale, double rest = 0) {
  Trajectory gt, est;
  const Eigen::Quaterniond R(Eigen::AngleAxisd(0.7, Eigen::Vector3d(0, 1, 1).normalized()));
  double xg = 0, xe = 0;
  for (int i = 0; i <= 600; ++i) {
    const double t = i / 30.0;
    if (i > 0 && t > rest) {
      xg += 1.0 / 30;
      xe += scale(t - 0.5 / 30) / 30;
    }
    gt.push_back(100 + t, SE3(Eigen::Quaterniond::Identity(), Eigen::Vector3d(xg, 0, 0)));
    est.push_back(100 + t, SE3(R, R * Eigen::Vector3d(xe, 0, 0)));
  }
  return {gt, est};
}

TEST(ScaleDrift, NoneForAConstantScale) {
  const auto [gt, est] = walk([](double) { return 0.4; });
  const ScaleDriftResult r = compute_scale_drift(gt, est, associate(gt, est, {}));
  ASSERT_TRUE(r.valid);
  EXPECT_EQ(r.ratios.size(), 20u);
  EXPECT_NEAR(r.slope_percent_per_second, 0.0, 1e-9);
  EXPECT_NEAR(r.slope_se_percent_per_second, 0.0, 1e-9);
  for (double x : r.ratios) EXPECT_NEAR(x, 1.0, 1e-9);
}

TEST(ScaleDrift, SlopeOfALinearShrink) {
  // Speed 1 - 0.003 t: each window's ratio is the speed at its middle, 0.97 on average.
  const auto [gt, est] = walk([](double t) { return 1.0 - 0.003 * t; });
  const ScaleDriftResult r = compute_scale_drift(gt, est, associate(gt, est, {}));
  ASSERT_TRUE(r.valid);
  EXPECT_NEAR(r.slope_percent_per_second, -100 * 0.003 / 0.97, 1e-3);
  EXPECT_NEAR(r.change_percent, r.slope_percent_per_second * 19, 1e-9);
  EXPECT_NEAR(r.times.front(), 0.5, 1e-9);
  EXPECT_LT(r.slope_se_percent_per_second, 1e-6);  // the ratios lie on the line
  // Two-second windows see the same line.
  EXPECT_NEAR(compute_scale_drift(gt, est, associate(gt, est, {}), 2.0).slope_percent_per_second,
              r.slope_percent_per_second, 1e-3);
}

TEST(ScaleDrift, StandardErrorOfScatteredRatios) {
  // Speeds alternating 0.98 / 1.02 from one second to the next: no trend, a scatter of 2 %.
  const auto [gt, est] = walk([](double t) { return static_cast<int>(t) % 2 ? 1.02 : 0.98; });
  const ScaleDriftResult r = compute_scale_drift(gt, est, associate(gt, est, {}));
  ASSERT_TRUE(r.valid);
  ASSERT_EQ(r.ratios.size(), 20u);
  // Least squares by hand: slope sum((t - tm) y) / sum((t - tm)^2), residuals about that line.
  double tm = 0, ym = 0, sxy = 0, sxx = 0, ss = 0;
  for (size_t k = 0; k < 20; ++k) tm += r.times[k] / 20, ym += r.ratios[k] / 20;
  for (size_t k = 0; k < 20; ++k) sxy += (r.times[k] - tm) * (r.ratios[k] - ym), sxx += std::pow(r.times[k] - tm, 2);
  for (size_t k = 0; k < 20; ++k) ss += std::pow(r.ratios[k] - ym - sxy / sxx * (r.times[k] - tm), 2);
  EXPECT_NEAR(r.slope_percent_per_second, 100 * sxy / sxx, 1e-9);
  EXPECT_NEAR(r.slope_se_percent_per_second, 100 * std::sqrt(ss / 18 / sxx), 1e-9);
  // About the scatter over the windows' spread in time: 0.02 / sqrt(20 (20^2 - 1) / 12) a second.
  EXPECT_NEAR(r.slope_se_percent_per_second, 100 * 0.02 / std::sqrt(665.0), 0.01);
  EXPECT_LT(std::abs(r.slope_percent_per_second), 2 * r.slope_se_percent_per_second);
}

TEST(ScaleDrift, StillWindowsAreSkippedAndTooFewAreNotValid) {
  const auto [gt, est] = walk([](double t) { return 1.0 + 0.002 * t; }, 5.0);
  const ScaleDriftResult r = compute_scale_drift(gt, est, associate(gt, est, {}));
  ASSERT_TRUE(r.valid);
  EXPECT_EQ(r.ratios.size(), 15u);  // the first five seconds do not move
  EXPECT_GT(r.slope_percent_per_second, 0.19);
  Trajectory short_gt, short_est;
  for (size_t i = 0; i < 60; ++i) short_gt.push_back(gt.timestamps[i + 300], gt.poses[i + 300]),
                                  short_est.push_back(est.timestamps[i + 300], est.poses[i + 300]);
  EXPECT_FALSE(compute_scale_drift(short_gt, short_est, associate(short_gt, short_est, {})).valid);  // 1 window
  Trajectory indexed = gt;
  indexed.indexed = true;
  EXPECT_FALSE(compute_scale_drift(indexed, est, associate(gt, est, {})).valid);
  EXPECT_THROW(compute_scale_drift(gt, est, associate(gt, est, {}), 0.0), std::invalid_argument);
}

TEST(TrackingRate, DurationCoveredByEstimates) {
  const Trajectory gt = circle(100, 100.0);  // 1 s at 100 Hz
  Trajectory est;
  for (int i = 0; i < 15; ++i) est.push_back(i / 30.0, gt.poses[0]);  // the first half second at 30 Hz
  const double r = tracking_rate(gt, est, {});
  EXPECT_NEAR(r, 50.0, 2.0);
  Trajectory full;
  for (int i = 0; i < 30; ++i) full.push_back(i / 30.0, gt.poses[0]);
  EXPECT_NEAR(tracking_rate(gt, full, {}), 100.0, 1.5);  // the ground truth runs 23 ms past the last frame
}

TEST(Plot, DrawsAReadableImage) {
  const Trajectory gt = circle(80, 30);
  PlotSeries g{"ground truth", {}, cv::Scalar(0, 0, 0)}, e{"estimate", {}, cv::Scalar(0, 0, 255)};
  for (const auto& p : gt.poses) g.points.push_back(p.translation()), e.points.push_back(p.translation() + Eigen::Vector3d(0.1, 0, 0));
  const cv::Mat img = plot_top_view({g, e}, "ATE RMSE 0.100 m");
  EXPECT_EQ(img.cols, 1000);
  // Both colours are present (the curves were drawn).
  cv::Mat red;
  cv::inRange(img, cv::Scalar(0, 0, 200), cv::Scalar(60, 60, 255), red);
  EXPECT_GT(cv::countNonZero(red), 500);
  const auto file = test::scratch_dir() / "plot.png";
  save_png(file, img);
  EXPECT_TRUE(std::filesystem::exists(file));
}

}  // namespace
}  // namespace wardmap::slam::eval
