#include "slam/core/sim3.h"

#include <gtest/gtest.h>

#include <random>

namespace wardmap::slam {
namespace {

Vector7d random_tangent(std::mt19937& rng) {
  std::normal_distribution<double> n(0.0, 0.7);
  Vector7d xi;
  for (int i = 0; i < 7; ++i) xi(i) = n(rng);
  return xi;
}

TEST(Sim3, ActsAsScaledRigid) {
  const Sim3 S(2.0, Eigen::Quaterniond(Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitZ())), Eigen::Vector3d(1, 0, 0));
  EXPECT_LT((S * Eigen::Vector3d(1, 0, 0) - Eigen::Vector3d(1, 2, 0)).norm(), 1e-12);
  EXPECT_LT(((S.inverse() * S) * Eigen::Vector3d(3, 4, 5) - Eigen::Vector3d(3, 4, 5)).norm(), 1e-12);
  EXPECT_THROW(Sim3(0.0, Eigen::Quaterniond::Identity(), Eigen::Vector3d::Zero()), std::invalid_argument);
}

TEST(Sim3, ExpLogRoundTripAndComposition) {
  std::mt19937 rng(7);
  for (int i = 0; i < 100; ++i) {
    const Vector7d xi = random_tangent(rng);
    if (xi.segment<3>(3).norm() > 3.0) continue;
    const Sim3 S = Sim3::exp(xi);
    EXPECT_NEAR(S.scale(), std::exp(xi(6)), 1e-12);
    EXPECT_LT((S.log() - xi).norm(), 1e-8) << xi.transpose();
    const Sim3 B = Sim3::exp(random_tangent(rng));
    EXPECT_LT(((S * B).matrix() - S.matrix() * B.matrix()).norm(), 1e-10);
  }
}

TEST(Sim3, ExpMatchesFiniteDifferenceOfGenerator) {
  std::mt19937 rng(8);
  const Vector7d xi = random_tangent(rng);
  const double h = 1e-6;
  const Eigen::Matrix4d d = (Sim3::exp(h * xi).matrix() - Sim3::exp(-h * xi).matrix()) / (2 * h);
  Eigen::Matrix4d G = Eigen::Matrix4d::Zero();
  G.topLeftCorner<3, 3>() = xi(6) * Eigen::Matrix3d::Identity() + hat(xi.segment<3>(3));
  G.topRightCorner<3, 1>() = xi.head<3>();
  EXPECT_LT((d - G).norm(), 1e-8);
}

TEST(Sim3, TransformPoseKeepsRotationRigid) {
  const Sim3 S(3.0, Eigen::Quaterniond(Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitY())), Eigen::Vector3d(1, 2, 3));
  const SE3 T(Eigen::Quaterniond(Eigen::AngleAxisd(0.2, Eigen::Vector3d::UnitX())), Eigen::Vector3d(0.5, 0, 1));
  const SE3 U = S.transform_pose(T);
  EXPECT_LT((U.translation() - S * T.translation()).norm(), 1e-12);
  EXPECT_NEAR(U.rotation_matrix().determinant(), 1.0, 1e-12);
}

}  // namespace
}  // namespace wardmap::slam
