#include "slam/core/umeyama.h"

#include <gtest/gtest.h>

#include <random>

namespace wardmap::slam {
namespace {

Eigen::Matrix3Xd random_points(std::mt19937& rng, int n) {
  std::uniform_real_distribution<double> u(-5, 5);
  Eigen::Matrix3Xd P(3, n);
  for (int i = 0; i < n; ++i) P.col(i) = Eigen::Vector3d(u(rng), u(rng), u(rng));
  return P;
}

Eigen::Matrix3Xd apply(const Sim3& S, const Eigen::Matrix3Xd& P) {
  Eigen::Matrix3Xd Q(3, P.cols());
  for (int i = 0; i < P.cols(); ++i) Q.col(i) = S * Eigen::Vector3d(P.col(i));
  return Q;
}

TEST(Umeyama, RecoversExactSim3) {
  std::mt19937 rng(11);
  const Sim3 truth(2.5, Eigen::Quaterniond(Eigen::AngleAxisd(2.0, Eigen::Vector3d(1, 2, 3).normalized())),
                   Eigen::Vector3d(-1, 4, 0.5));
  const Eigen::Matrix3Xd P = random_points(rng, 30);
  const Sim3 est = umeyama_sim3(P, apply(truth, P));
  EXPECT_NEAR(est.scale(), 2.5, 1e-10);
  EXPECT_LT((est.matrix() - truth.matrix()).norm(), 1e-9);
}

TEST(Umeyama, Se3KeepsUnitScale) {
  std::mt19937 rng(12);
  const Sim3 truth(1.0, Eigen::Quaterniond(Eigen::AngleAxisd(-1.0, Eigen::Vector3d::UnitX())), Eigen::Vector3d(3, 2, 1));
  const Eigen::Matrix3Xd P = random_points(rng, 10);
  const Sim3 est = umeyama_se3(P, apply(truth, P));
  EXPECT_DOUBLE_EQ(est.scale(), 1.0);
  EXPECT_LT((est.matrix() - truth.matrix()).norm(), 1e-9);
}

TEST(Umeyama, HandlesReflectionCase) {
  // Planar points with a mirrored target: the solution must stay a rotation (det +1).
  Eigen::Matrix3Xd P(3, 4), Q(3, 4);
  P << 0, 1, 0, 1, 0, 0, 1, 1, 0, 0, 0, 0;
  Q = P;
  Q.row(0) *= -1;
  const Sim3 est = umeyama_sim3(P, Q);
  EXPECT_NEAR(est.rotation().toRotationMatrix().determinant(), 1.0, 1e-12);
}

TEST(Umeyama, RejectsDegenerateInput) {
  Eigen::Matrix3Xd two(3, 2);
  two.setRandom();
  EXPECT_THROW(umeyama_sim3(two, two), std::invalid_argument);
  Eigen::Matrix3Xd line(3, 5);
  for (int i = 0; i < 5; ++i) line.col(i) = Eigen::Vector3d(i, 2 * i, 0);
  EXPECT_THROW(umeyama_sim3(line, line), std::invalid_argument);
}

}  // namespace
}  // namespace wardmap::slam
