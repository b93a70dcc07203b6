#include "semantics/pose_selection.h"

#include <gtest/gtest.h>

namespace wardmap::semantics {
namespace {

ObjectPose at(double x, double yaw_deg = 0) {
  return {slam::SE3(Eigen::Quaterniond(Eigen::AngleAxisd(yaw_deg * M_PI / 180, Eigen::Vector3d::UnitZ())),
                    Eigen::Vector3d(x, 0, 0)),
          Eigen::Vector3d::Ones()};
}

TEST(PoseSelection, Eq4To6KnownValues) {
  PoseSelectionOptions o;  // A = 45 deg, B = 1 m, alpha 0.4, beta 0.6
  const std::vector<ObjectPose> poses = {at(0.0), at(0.2, 9), at(2.0, 90)};
  const auto f = pose_differences(poses, o);
  // k = 0: angles 9/45 = 0.2 and 90 -> 1 (clipped); distances 0.2 and 2 -> 1 (clipped).
  EXPECT_NEAR(f[0], 0.4 * (0.2 + 1.0) / 2 + 0.6 * (0.2 + 1.0) / 2, 1e-12);
  // k = 1: angles 0.2 and 81/45 -> 1; distances 0.2 and 1.8 -> 1.
  EXPECT_NEAR(f[1], 0.4 * (0.2 + 1.0) / 2 + 0.6 * (0.2 + 1.0) / 2, 1e-12);
  // k = 2: everything clipped to 1.
  EXPECT_NEAR(f[2], 1.0, 1e-12);
  EXPECT_EQ(select_landmark_pose(poses, o), 0);  // tie between 0 and 1 goes to the earlier
}

TEST(PoseSelection, PicksTheConsensusNotTheFirst) {
  PoseSelectionOptions o;
  const std::vector<ObjectPose> poses = {at(1.5, 30), at(0.05), at(-0.05), at(0.0, 2), at(0.1, -3)};
  // f[1] = 0.4 (30 + 0 + 2 + 3) / 45 / 4 + 0.6 (1 + 0.1 + 0.05 + 0.05) / 4 = 0.2578
  // f[3] = 0.4 (28 + 2 + 2 + 5) / 45 / 4 + 0.6 (1 + 0.05 + 0.05 + 0.1) / 4 = 0.2622; the outlier 0 is worst.
  const auto f = pose_differences(poses, o);
  EXPECT_NEAR(f[1], 0.4 * 35.0 / 45 / 4 + 0.6 * 1.2 / 4, 1e-9);
  EXPECT_NEAR(f[3], 0.4 * 37.0 / 45 / 4 + 0.6 * 1.2 / 4, 1e-9);
  EXPECT_EQ(select_landmark_pose(poses, o), 1);
  EXPECT_EQ(select_landmark_pose({}, o), -1);
  EXPECT_EQ(select_landmark_pose({at(4)}, o), 0);
}

TEST(PoseSelection, HalfTurnOfABoxIsTheSameOrientation) {
  EXPECT_NEAR(object_angle_difference(at(0, 0).pose, at(0, 180).pose), 0.0, 1e-9);
  EXPECT_NEAR(object_angle_difference(at(0, 10).pose, at(0, 170).pose), 20 * M_PI / 180, 1e-9);
}

}  // namespace
}  // namespace wardmap::semantics
