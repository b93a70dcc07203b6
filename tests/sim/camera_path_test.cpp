// Camera paths: conventions (camera-to-world, OpenCV axes, z-up world), waypoints hit, smooth motion.
#include "sim/camera_path.h"

#include <gtest/gtest.h>

#include "tests/sim/sim_test_util.h"

namespace wardmap::sim {
namespace {

TEST(CameraPath, RotationConvention) {
  const Eigen::Matrix3d R = camera_rotation(0, 0, 0);
  EXPECT_TRUE(R.col(2).isApprox(Eigen::Vector3d::UnitX()));   // looks along +x
  EXPECT_TRUE(R.col(1).isApprox(-Eigen::Vector3d::UnitZ()));  // image down = world down
  EXPECT_TRUE(R.col(0).isApprox(-Eigen::Vector3d::UnitY()));  // image right
  const Eigen::Matrix3d L = camera_rotation(M_PI / 2, 0.3, 0);
  EXPECT_NEAR(L.col(2).x(), 0.0, 1e-12);
  EXPECT_NEAR(L.col(2).z(), std::sin(0.3), 1e-12);  // positive pitch looks up
  EXPECT_NEAR(L.determinant(), 1.0, 1e-12);
}

TEST(CameraPath, MonotoneSplineHitsKnotsWithoutOvershoot) {
  const MonotoneSpline s({0, 1, 2, 3}, {0, 1, 1, 5});
  EXPECT_DOUBLE_EQ(s(1.0), 1.0);
  for (double t = 1.0; t <= 2.0; t += 0.01) EXPECT_NEAR(s(t), 1.0, 1e-12);  // flat stays flat
  double prev = -1;
  for (double t = 0; t <= 3.0; t += 0.01) {
    EXPECT_GE(s(t), prev - 1e-12);
    prev = s(t);
  }
}

TEST(CameraPath, WaypointsAndSmoothness) {
  const Scenario sc = testing::builtin("aisle_left_turn");
  for (const Variant v : {Variant::kSlow, Variant::kQuick}) {
    const CameraPath path(sc, v, 3);
    for (size_t i = 0; i < sc.waypoints.size(); ++i) {
      const slam::SE3 T = path.pose(path.waypoint_time(static_cast<int>(i)));
      EXPECT_LT((T.translation() - sc.waypoints[i].position).norm(), 0.01);
      const Eigen::Vector3d f = T.rotation_matrix().col(2);
      EXPECT_NEAR(std::atan2(f.y(), f.x()) * 180 / M_PI, sc.waypoints[i].yaw_deg, 1.0);
    }
    // no jumps between frames: under 0.2 m and 10 degrees per frame in this scenario
    for (double t = 0; t + 1 / 30.0 < path.duration(); t += 1 / 30.0) {
      const slam::SE3 a = path.pose(t), b = path.pose(t + 1 / 30.0);
      EXPECT_LT((a.translation() - b.translation()).norm(), 0.2);
      EXPECT_LT(slam::rotation_angle(a.rotation().inverse() * b.rotation()), 10 * M_PI / 180);
    }
  }
  const CameraPath slow(sc, Variant::kSlow, 3), quick(sc, Variant::kQuick, 3);
  EXPECT_NEAR(quick.duration(), 0.5 * slow.duration(), 1e-9);
  EXPECT_GT(slow.duration() * 30, 300);
  EXPECT_LT(slow.duration() * 30, 450);
}

}  // namespace
}  // namespace wardmap::sim
