#include "slam/core/se3.h"

#include <gtest/gtest.h>

#include <random>

namespace wardmap::slam {
namespace {

Vector6d random_twist(std::mt19937& rng, double scale = 1.0) {
  std::normal_distribution<double> n(0.0, scale);
  Vector6d xi;
  for (int i = 0; i < 6; ++i) xi(i) = n(rng);
  return xi;
}

TEST(SE3, ExpOfKnownTwist) {
  // A quarter turn about z with translation rho: t = V rho, V for theta = pi/2 known in closed form.
  Vector6d xi;
  xi << 1, 0, 0, 0, 0, M_PI / 2;
  const SE3 T = SE3::exp(xi);
  EXPECT_NEAR((T * Eigen::Vector3d(1, 0, 0) - Eigen::Vector3d(0, 1, 0) - T.translation()).norm(), 0, 1e-12);
  // V = I + (1 - cos)/th^2 K + (th - sin)/th^3 K^2, K = hat(z * th) => V (1,0,0) = (sin th / th, (1 - cos th)/th, 0)
  const double th = M_PI / 2;
  EXPECT_NEAR(T.translation().x(), std::sin(th) / th, 1e-12);
  EXPECT_NEAR(T.translation().y(), (1 - std::cos(th)) / th, 1e-12);
  EXPECT_NEAR(T.translation().z(), 0, 1e-12);
}

TEST(SE3, ExpLogRoundTrip) {
  std::mt19937 rng(1);
  for (int i = 0; i < 200; ++i) {
    Vector6d xi = random_twist(rng, 0.8);
    if (xi.tail<3>().norm() > 3.0) continue;  // log is defined on angles < pi
    EXPECT_LT((SE3::exp(xi).log() - xi).norm(), 1e-9) << xi.transpose();
  }
  Vector6d tiny = random_twist(rng, 1e-10);
  EXPECT_LT((SE3::exp(tiny).log() - tiny).norm(), 1e-15);
}

TEST(SE3, ComposeInverseAct) {
  std::mt19937 rng(2);
  for (int i = 0; i < 50; ++i) {
    const SE3 a = SE3::exp(random_twist(rng)), b = SE3::exp(random_twist(rng));
    const Eigen::Vector3d p(0.3, -1.2, 2.5);
    EXPECT_LT(((a * b) * p - a * (b * p)).norm(), 1e-12);
    EXPECT_LT(((a * a.inverse()).log()).norm(), 1e-12);
    EXPECT_LT(((a * b).matrix() - a.matrix() * b.matrix()).norm(), 1e-12);
    EXPECT_LT((SE3::from_matrix(a.matrix()).matrix() - a.matrix()).norm(), 1e-12);
  }
}

TEST(SE3, ExpMatchesFiniteDifferenceOfGenerator) {
  // d/dt exp(t xi) at t = 0 equals the generator [[hat(phi), rho], [0, 0]].
  std::mt19937 rng(3);
  const Vector6d xi = random_twist(rng);
  const double h = 1e-6;
  const Eigen::Matrix4d d = (SE3::exp(h * xi).matrix() - SE3::exp(-h * xi).matrix()) / (2 * h);
  Eigen::Matrix4d G = Eigen::Matrix4d::Zero();
  G.topLeftCorner<3, 3>() = hat(xi.tail<3>());
  G.topRightCorner<3, 1>() = xi.head<3>();
  EXPECT_LT((d - G).norm(), 1e-8);
}

TEST(SE3, InterpolateEndpointsAndMidpoint) {
  Vector6d xi;
  xi << 2, 0, 0, 0, 0, 1.0;
  const SE3 a, b = SE3::exp(xi);
  EXPECT_LT((SE3::interpolate(a, b, 0).matrix() - a.matrix()).norm(), 1e-12);
  EXPECT_LT((SE3::interpolate(a, b, 1).matrix() - b.matrix()).norm(), 1e-12);
  const SE3 m = SE3::interpolate(a, b, 0.5);
  EXPECT_NEAR(rotation_angle(m.rotation()), 0.5, 1e-12);
  EXPECT_LT((m.translation() - 0.5 * b.translation()).norm(), 1e-12);
}

TEST(SE3, FromMatrixReorthonormalises) {
  Eigen::Matrix4d T = SE3::exp((Vector6d() << 1, 2, 3, 0.1, 0.2, 0.3).finished()).matrix();
  T(0, 0) += 1e-7;  // rounding in a pose file
  const Eigen::Matrix3d R = SE3::from_matrix(T).rotation_matrix();
  EXPECT_LT((R * R.transpose() - Eigen::Matrix3d::Identity()).norm(), 1e-12);
  EXPECT_NEAR(R.determinant(), 1.0, 1e-12);
}

}  // namespace
}  // namespace wardmap::slam
