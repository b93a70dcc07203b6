#include "slam/core/camera.h"

#include <gtest/gtest.h>

namespace wardmap::slam {
namespace {

PinholeCamera kitti_like() {
  PinholeCamera c;
  c.fx = 718.856; c.fy = 718.856; c.cx = 607.19; c.cy = 185.22;
  c.width = 1241; c.height = 376;
  return c;
}

PinholeCamera tum_fr1() {  // TUM fr1 colour camera, with its published distortion
  PinholeCamera c;
  c.fx = 517.306408; c.fy = 516.469215; c.cx = 318.643040; c.cy = 255.313989;
  c.k1 = 0.262383; c.k2 = -0.953104; c.p1 = -0.005358; c.p2 = 0.002628; c.k3 = 1.163314;
  c.width = 640; c.height = 480;
  return c;
}

TEST(PinholeCamera, ProjectsKnownPoint) {
  const PinholeCamera c = kitti_like();
  const Eigen::Vector2d px = c.project(Eigen::Vector3d(1, -0.5, 10));
  EXPECT_NEAR(px.x(), 607.19 + 71.8856, 1e-9);
  EXPECT_NEAR(px.y(), 185.22 - 35.9428, 1e-9);
  EXPECT_FALSE(c.validate().has_value());
}

TEST(PinholeCamera, UnprojectInvertsProjectWithDistortion) {
  const PinholeCamera c = tum_fr1();
  for (double x = -0.5; x <= 0.5; x += 0.1)
    for (double y = -0.4; y <= 0.4; y += 0.1) {
      const Eigen::Vector3d p(x * 3, y * 3, 3);
      const Eigen::Vector3d ray = c.unproject(c.project(p));
      EXPECT_LT((ray - p / p.z()).norm(), 1e-10) << x << " " << y;
    }
}

TEST(PinholeCamera, UndistortPointMatchesIdealPinhole) {
  const PinholeCamera c = tum_fr1();
  PinholeCamera ideal = c;
  ideal.k1 = ideal.k2 = ideal.p1 = ideal.p2 = ideal.k3 = 0;
  const Eigen::Vector3d p(0.4, 0.3, 1.2);
  EXPECT_LT((c.undistort_point(c.project(p)) - ideal.project(p)).norm(), 1e-8);
}

TEST(PinholeCamera, ProjectJacobianMatchesFiniteDifferences) {
  const PinholeCamera c = tum_fr1();
  const Eigen::Vector3d p(0.3, -0.2, 1.7);
  const Eigen::Matrix<double, 2, 3> J = c.project_jacobian(p);
  const double h = 1e-6;
  for (int k = 0; k < 3; ++k) {
    Eigen::Vector3d d = Eigen::Vector3d::Zero();
    d(k) = h;
    const Eigen::Vector2d fd = (c.project(p + d) - c.project(p - d)) / (2 * h);
    EXPECT_LT((fd - J.col(k)).norm(), 1e-5) << "column " << k;
  }
}

TEST(PinholeCamera, ValidateNamesTheBadParameter) {
  PinholeCamera c = kitti_like();
  c.fx = -1;
  ASSERT_TRUE(c.validate().has_value());
  EXPECT_NE(c.validate()->find("fx"), std::string::npos);
  c = kitti_like();
  c.cx = 5000;
  EXPECT_NE(c.validate()->find("cx"), std::string::npos);
}

}  // namespace
}  // namespace wardmap::slam
