// Object pose from depth (Assoc. Eq. 1) on rendered depth of known boxes.
#include <gtest/gtest.h>

#include "tests/support/test_camera.h"
#include "semantics/object_measurement.h"

namespace wardmap::semantics {
namespace {

slam::PinholeCamera camera() { return test::vga_camera(); }

// Depth of a scene: a wall at z = wall, and an axis-aligned box face (front at z = front) covering
// pixels [x0, x1) x [y0, y1). Camera at the origin looking along +z (y down), world = camera frame.
cv::Mat scene(double wall, double front, int x0, int x1, int y0, int y1) {
  cv::Mat d(480, 640, CV_32F, cv::Scalar(wall));
  d(cv::Rect(x0, y0, x1 - x0, y1 - y0)).setTo(front);
  return d;
}

TEST(Measurement, PlacesTheFrontFaceAndCompletesItsDepth) {
  SemanticOptions o;
  const slam::SE3 T;  // camera = world
  const Eigen::Vector3d up(0, -1, 0);
  const cv::Mat d = scene(6.0, 3.0, 220, 420, 140, 340);  // a 1.2 m square face at 3 m
  const auto p = measure_pose_from_depth(d, camera(), T, Eigen::Vector4d(220, 140, 420, 340), up, "cabinet", o);
  ASSERT_TRUE(p);
  // Centre of the face at x = 0, y = 0; pushed back by half the cabinet's typical depth (0.45 / 2).
  EXPECT_NEAR(p->pose.translation().x(), 0.0, 0.03);
  EXPECT_NEAR(p->pose.translation().y(), 0.0, 0.03);
  EXPECT_NEAR(p->pose.translation().z(), 3.0 + 0.225, 0.03);
  // Height: the 5-95 % extent of the trimmed face (1.2 m less 2 x 20 %, less the 10 % tails).
  EXPECT_NEAR(p->size.z(), 1.2 * 0.6 * 0.9, 0.05);
  // Up of the object is the world's up.
  EXPECT_NEAR(p->pose.rotation_matrix().col(2).dot(up), 1.0, 1e-9);
}

TEST(Measurement, NoPoseForDegenerateInput) {
  SemanticOptions o;
  const Eigen::Vector3d up(0, -1, 0);
  cv::Mat empty(480, 640, CV_32F, cv::Scalar(0));
  EXPECT_FALSE(measure_pose_from_depth(empty, camera(), slam::SE3(), Eigen::Vector4d(200, 100, 400, 300), up, "door", o));
  EXPECT_FALSE(measure_pose_from_depth(cv::Mat(), camera(), slam::SE3(), Eigen::Vector4d(200, 100, 400, 300), up, "door", o));
  const cv::Mat d = scene(5, 2, 0, 100, 100, 300);
  // Cut off by the left border.
  EXPECT_FALSE(measure_pose_from_depth(d, camera(), slam::SE3(), Eigen::Vector4d(0, 100, 100, 300), up, "door", o));
  // A 3x3 pixel box.
  EXPECT_FALSE(measure_pose_from_depth(d, camera(), slam::SE3(), Eigen::Vector4d(300, 200, 303, 203), up, "door", o));
}

TEST(Measurement, NearerOverlappingDetectionIsLeftOut) {
  SemanticOptions o;
  o.measurement.complete_depth_with_class_size = false;
  const Eigen::Vector3d up(0, -1, 0);
  // Far object [200, 400) at 5 m, partly hidden by a near one [320, 440) at 2 m that reaches lower.
  cv::Mat d = scene(8.0, 5.0, 200, 400, 150, 300);
  d(cv::Rect(320, 200, 120, 150)).setTo(2.0);
  const std::vector<Eigen::Vector4d> boxes = {Eigen::Vector4d(200, 150, 400, 300), Eigen::Vector4d(320, 200, 440, 350)};
  const auto occ = nearer_overlapping_boxes(d, boxes, o.measurement);
  ASSERT_EQ(occ[0].size(), 1u);
  EXPECT_TRUE(occ[1].empty());
  const auto p = measure_pose_from_depth(d, camera(), slam::SE3(), boxes[0], up, "chair", o, occ[0]);
  ASSERT_TRUE(p);
  EXPECT_NEAR(p->pose.translation().z(), 5.0, 0.05);
}

TEST(Measurement, UpFromCameraPoses) {
  // Upright cameras looking along world x in a z-up world: camera y (down) = world -z.
  Eigen::Matrix3d R;
  R << 0, 0, 1, -1, 0, 0, 0, -1, 0;
  const slam::SE3 T(R, Eigen::Vector3d(1, 2, 1.2));
  EXPECT_LT((estimate_up({T, T}) - Eigen::Vector3d::UnitZ()).norm(), 1e-12);
}

}  // namespace
}  // namespace wardmap::semantics
