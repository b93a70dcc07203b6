// Two-view initialisation on synthetic correspondences with a known motion: the right model is
// chosen (F for a scene with depth; a plane scores for H), the motion is recovered, and a rotation-only
// pair (no parallax) is refused.
#include "slam/front/two_view.h"

#include <gtest/gtest.h>

#include <random>

#include "tests/support/test_camera.h"

namespace wardmap::slam {

namespace {

struct Pairs {
  std::vector<Eigen::Vector2d> p1, p2;
};

// Projects world points (camera 1 = world) with noise; `outliers` of them get a random pixel in view 2.
Pairs project(const std::vector<Eigen::Vector3d>& X, const SE3& T21, const PinholeCamera& cam, double noise,
              int outliers, std::mt19937& rng) {
  std::normal_distribution<double> n(0, noise);
  std::uniform_real_distribution<double> u(0, 640), v(0, 480);
  Pairs p;
  for (size_t i = 0; i < X.size(); ++i) {
    const Eigen::Vector3d x2 = T21 * X[i];
    Eigen::Vector2d a(cam.fx * X[i].x() / X[i].z() + cam.cx, cam.fy * X[i].y() / X[i].z() + cam.cy);
    Eigen::Vector2d b(cam.fx * x2.x() / x2.z() + cam.cx, cam.fy * x2.y() / x2.z() + cam.cy);
    a += Eigen::Vector2d(n(rng), n(rng));
    b += Eigen::Vector2d(n(rng), n(rng));
    if (static_cast<int>(i) < outliers) b = {u(rng), v(rng)};
    p.p1.push_back(a);
    p.p2.push_back(b);
  }
  return p;
}

double angle_deg(const Eigen::Quaterniond& a, const Eigen::Quaterniond& b) {
  return a.angularDistance(b) * 180.0 / M_PI;
}

SE3 motion(double yaw_deg, const Eigen::Vector3d& t) {
  return SE3(Eigen::Quaterniond(Eigen::AngleAxisd(yaw_deg * M_PI / 180, Eigen::Vector3d::UnitY())), t);
}

}  // namespace

TEST(TwoView, DepthSceneUsesTheFundamentalMatrixAndRecoversTheMotion) {
  const PinholeCamera cam = test::vga_camera();
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> x(-2, 2), y(-1.5, 1.5), z(3, 8);
  std::vector<Eigen::Vector3d> X;
  for (int i = 0; i < 400; ++i) X.emplace_back(x(rng), y(rng), z(rng));
  const SE3 T21 = motion(3, Eigen::Vector3d(-0.3, 0.02, -0.05));
  const Pairs p = project(X, T21, cam, 0.7, 40, rng);
  const auto r = reconstruct_two_views(p.p1, p.p2, cam, TwoViewOptions{});
  ASSERT_TRUE(r.has_value());
  EXPECT_FALSE(r->homography) << "S_H share " << r->homography_share;
  // Linear estimates (before any bundle adjustment) with 0.7 px noise.
  EXPECT_LT(angle_deg(r->T_21.rotation(), T21.rotation()), 1.0);
  const double t_angle = std::acos(std::clamp(r->T_21.translation().dot(T21.translation().normalized()), -1.0, 1.0));
  EXPECT_LT(t_angle * 180 / M_PI, 3.0);
  EXPECT_GT(r->good, 300);
  // Points are up to the scale |t| = 1 of the reconstruction.
  const double s = T21.translation().norm();
  int close = 0;
  for (size_t i = 40; i < X.size(); ++i)
    if (r->triangulated[i] && (s * r->points[i] - X[i]).norm() < 0.15 * X[i].z()) ++close;
  EXPECT_GT(close, 250);
  for (int i = 0; i < 40; ++i) EXPECT_FALSE(r->triangulated[static_cast<size_t>(i)] && r->points[static_cast<size_t>(i)].z() > 0 &&
                                            (s * r->points[static_cast<size_t>(i)] - X[static_cast<size_t>(i)]).norm() < 0.01)
      << "an outlier pair landed on its true point " << i;
}

TEST(TwoView, PlanarSceneFavoursTheHomography) {
  const PinholeCamera cam = test::vga_camera();
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> x(-3, 3), z(2.5, 12);
  std::vector<Eigen::Vector3d> X;
  for (int i = 0; i < 300; ++i) X.emplace_back(x(rng), 1.2, z(rng));  // the floor, 1.2 m below the camera
  const SE3 T21 = motion(-2, Eigen::Vector3d(0.3, 0.0, -0.2));
  const Pairs p = project(X, T21, cam, 0.5, 0, rng);
  std::vector<char> in;
  const double sh = score_homography(homography_dlt(p.p1, p.p2), p.p1, p.p2, 1.0, in);
  EXPECT_GT(std::count(in.begin(), in.end(), 1), 270);
  const double sf = score_fundamental(fundamental_8point(p.p1, p.p2), p.p1, p.p2, 1.0, in);
  EXPECT_GT(sh / (sh + sf), TwoViewOptions{}.homography_share);
  // A plane has two motions that explain the views equally well; either the reconstruction refuses
  // the pair (ORB-SLAM's rule: a second motion with 70 % of the points) or it returns the true one.
  const auto r = reconstruct_two_views(p.p1, p.p2, cam, TwoViewOptions{});
  if (r) {
    EXPECT_TRUE(r->homography);
    EXPECT_LT(angle_deg(r->T_21.rotation(), T21.rotation()), 0.5);
  }
}

TEST(TwoView, PureRotationIsRefused) {
  const PinholeCamera cam = test::vga_camera();
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> x(-2, 2), y(-1.5, 1.5), z(3, 8);
  std::vector<Eigen::Vector3d> X;
  for (int i = 0; i < 300; ++i) X.emplace_back(x(rng), y(rng), z(rng));
  const Pairs p = project(X, motion(5, Eigen::Vector3d::Zero()), cam, 0.5, 0, rng);
  EXPECT_FALSE(reconstruct_two_views(p.p1, p.p2, cam, TwoViewOptions{}).has_value());
}

TEST(TwoView, MinimalSolversFitExactData) {
  const PinholeCamera cam = test::vga_camera();
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> x(-2, 2), y(-1.5, 1.5), z(3, 8);
  std::vector<Eigen::Vector3d> X;
  for (int i = 0; i < 8; ++i) X.emplace_back(x(rng), y(rng), z(rng));
  const Pairs p = project(X, motion(2, Eigen::Vector3d(0.2, 0, 0.1)), cam, 0.0, 0, rng);
  const Eigen::Matrix3d F = fundamental_8point(p.p1, p.p2);
  for (size_t i = 0; i < 8; ++i) {
    const Eigen::Vector3d l = F * p.p1[i].homogeneous();
    EXPECT_LT(std::abs(l.dot(p.p2[i].homogeneous())) / l.head<2>().norm(), 1e-6);
  }
  std::vector<char> in;
  score_fundamental(F, p.p1, p.p2, 1.0, in);
  EXPECT_EQ(std::count(in.begin(), in.end(), 1), 8);
}

}  // namespace wardmap::slam
