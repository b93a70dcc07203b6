#include "mot/kalman_box_filter.h"

#include <gtest/gtest.h>

#include <random>

namespace wardmap::mot {
namespace {

TEST(KalmanBoxFilter, CornersRoundTrip) {
  const Vector4d c(10, 20, 50, 100);
  const Vector4d z = corners_to_xyah(c);
  EXPECT_NEAR(z(0), 30, 1e-12);
  EXPECT_NEAR(z(1), 60, 1e-12);
  EXPECT_NEAR(z(2), 0.5, 1e-12);
  EXPECT_NEAR(z(3), 80, 1e-12);
  EXPECT_LT((xyah_to_corners(z) - c).norm(), 1e-12);
}

TEST(KalmanBoxFilter, ConvergesOnConstantVelocityBox) {
  const KalmanBoxFilter kf;
  const Vector4d v(4.0, -2.0, 0.0, 0.5);  // per-frame velocity of (cx, cy, a, h)
  Vector4d z(100, 200, 0.5, 80);
  BoxState s = kf.initiate(z);
  std::mt19937 rng(3);
  std::normal_distribution<double> noise(0.0, 0.5);
  for (int f = 0; f < 60; ++f) {
    kf.predict(s);
    z += v;
    Vector4d meas = z;
    meas(0) += noise(rng);
    meas(1) += noise(rng);
    kf.update(s, meas);
  }
  EXPECT_NEAR(s.mean(4), v(0), 0.3);
  EXPECT_NEAR(s.mean(5), v(1), 0.3);
  EXPECT_NEAR(s.mean(7), v(3), 0.1);
  EXPECT_LT((s.mean.head<2>() - z.head<2>()).norm(), 1.5);
  // A prediction one frame ahead lands on the true next box.
  BoxState ahead = s;
  kf.predict(ahead);
  EXPECT_LT((ahead.mean.head<2>() - (z + v).head<2>()).norm(), 1.5);
  EXPECT_LT(kf.gating_distance(ahead, z + v), kChi2Inv95Dof4);
}

TEST(KalmanBoxFilter, ExactMeasurementsWithoutNoiseGiveExactVelocity) {
  const KalmanBoxFilter kf;
  Vector4d z(0, 0, 1.0, 50);
  BoxState s = kf.initiate(z);
  for (int f = 0; f < 200; ++f) {
    kf.predict(s);
    z(0) += 3;
    kf.update(s, z);
  }
  EXPECT_NEAR(s.mean(4), 3.0, 1e-3);
  EXPECT_NEAR(s.mean(0), z(0), 1e-2);
}

TEST(KalmanBoxFilter, GatingGrowsWithDistanceAndShrinksWithTime) {
  const KalmanBoxFilter kf;
  const Vector4d z(100, 100, 0.5, 100);
  BoxState s = kf.initiate(z);
  kf.predict(s);
  Vector4d near = z, far = z;
  near(0) += 5;
  far(0) += 50;
  EXPECT_LT(kf.gating_distance(s, near), kf.gating_distance(s, far));
  EXPECT_LT(kf.gating_distance(s, far, true), kf.gating_distance(s, far) + 1e-9);
  // A longer gap (dt) widens the covariance, so the same offset is less surprising.
  BoxState later = kf.initiate(z);
  kf.predict(later, 5.0);
  EXPECT_LT(kf.gating_distance(later, far), kf.gating_distance(s, far));
}

TEST(KalmanBoxFilter, OptionsNameTheBadField) {
  KalmanBoxOptions o;
  o.std_weight_velocity = -1;
  ASSERT_TRUE(o.validate().has_value());
  EXPECT_NE(o.validate()->find("std_weight_velocity"), std::string::npos);
  EXPECT_THROW(KalmanBoxFilter{o}, std::invalid_argument);
}

}  // namespace
}  // namespace wardmap::mot
