// Monocular object measurements: sparse depth from map points and the metric scale from upright
// detections (semantics/monocular_scale.h).
#include <gtest/gtest.h>

#include <random>

#include "semantics/monocular_scale.h"
#include "semantics/object_measurement.h"
#include "tests/support/test_camera.h"

namespace wardmap::semantics {
namespace {

slam::PinholeCamera camera() { return test::vga_camera(); }

TEST(SparseDepth, PaintsSquaresNearestFirstAndScalesDepths) {
  const auto cam = camera();
  // Two points on one pixel's ray at depths 2 and 3 (map units), one behind the camera.
  const Eigen::Vector3d ray = cam.unproject(Eigen::Vector2d(100, 200));
  const std::vector<Eigen::Vector3d> pts = {ray * 3.0, ray * 2.0, Eigen::Vector3d(0, 0, -1),
                                            Eigen::Vector3d(1e12, 0, 1e-3)};  // far outside the image
  const cv::Mat d = sparse_depth_image(pts, cam, 2, 1.5);
  ASSERT_EQ(d.type(), CV_32F);
  EXPECT_FLOAT_EQ(d.at<float>(200, 100), 3.0f);  // 2 units x 1.5 m per unit: the nearer point wins
  EXPECT_FLOAT_EQ(d.at<float>(202, 98), 3.0f);   // inside the 5 x 5 square
  EXPECT_FLOAT_EQ(d.at<float>(203, 100), 0.0f);  // outside it
  EXPECT_EQ(cv::countNonZero(d), 25);  // the points behind the camera and outside the image paint nothing
}

TEST(SparseDepth, ScaleClassesHaveATypicalSize) {
  SemanticOptions o;
  EXPECT_TRUE(scale_class("door", o));
  EXPECT_TRUE(scale_class("chair", o));
  EXPECT_TRUE(scale_class("vehicle", o));
  EXPECT_FALSE(scale_class("bed", o));  // its box height shows its length
  EXPECT_FALSE(scale_class("tv", o));   // its width
  o.monocular.scale_classes.insert("plant");
  EXPECT_FALSE(scale_class("plant", o));  // no typical size
}

// A door (2.05 m tall) at 4 m seen by a map whose unit is 2.5 m: its points are at 1.6 units, and
// the wall behind it, at 2.4 units, holds as many points as the door. The estimate is 2.5 m per unit.
TEST(MetricScale, RecoversTheUnitFromAnUprightBox) {
  const auto cam = camera();
  SemanticOptions o;
  const double unit = 2.5, depth_m = 4.0;
  const double h_px = 2.05 * cam.fy / depth_m;  // the door's box height in pixels
  const Eigen::Vector4d box(250, 240 - h_px / 2, 250 + 0.9 * cam.fx / depth_m, 240 + h_px / 2);
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(box(0), box(2)), v(box(1), box(3));
  std::vector<Eigen::Vector3d> pts;
  for (int i = 0; i < 40; ++i) pts.push_back(cam.unproject(Eigen::Vector2d(u(rng), v(rng))) * (depth_m / unit));
  for (int i = 0; i < 40; ++i) pts.push_back(cam.unproject(Eigen::Vector2d(u(rng), v(rng))) * (6.0 / unit));
  const auto s = scale_estimate(pts, cam, box, "door", o);
  ASSERT_TRUE(s);
  EXPECT_NEAR(*s, unit, 0.01 * unit);
  // No estimate from a box cut at the top, a class whose box is not its height, or too few points.
  Eigen::Vector4d cut = box;
  cut(1) = 0;
  EXPECT_FALSE(scale_estimate(pts, cam, cut, "door", o));
  EXPECT_FALSE(scale_estimate(pts, cam, box, "bed", o));
  const std::vector<Eigen::Vector3d> few(pts.begin(), pts.begin() + 3);
  EXPECT_FALSE(scale_estimate(few, cam, box, "door", o));
}

// A box another detection overlaps (a chair behind a table shows only its back) gives no estimate;
// a box alone does.
TEST(MetricScale, OverlappedBoxesGiveNoEstimate) {
  const auto cam = camera();
  SemanticOptions o;
  const Eigen::Vector4d door(250, 100, 330, 380);
  std::vector<Eigen::Vector3d> pts;
  for (int y = 160; y < 330; y += 20)
    for (int x = 270; x < 315; x += 10) pts.push_back(cam.unproject(Eigen::Vector2d(x, y)) * 2.0);
  EXPECT_EQ(keyframe_scale_estimates(pts, cam, {door}, {"door"}, o).size(), 1u);
  const Eigen::Vector4d table(200, 300, 500, 420);  // covers the door's bottom 80 rows: 29 % of it
  const auto e = keyframe_scale_estimates(pts, cam, {door, table}, {"door", "table"}, o);
  EXPECT_TRUE(e.empty());
  const Eigen::Vector4d far_box(500, 100, 600, 200);  // apart from the door: no effect
  EXPECT_EQ(keyframe_scale_estimates(pts, cam, {door, far_box}, {"door", "chair"}, o).size(), 1u);
}

TEST(MetricScale, MedianOfEnoughEstimates) {
  MonocularOptions o;
  o.min_scale_estimates = 3;
  EXPECT_FALSE(metric_scale({1.0, 2.0}, o));
  EXPECT_DOUBLE_EQ(*metric_scale({9.0, 1.0, 2.0, 2.1, 1.9}, o), 2.0);
}

// The whole monocular measurement: points of a cabinet face in map units, painted at the estimated
// scale, measured with the sparse options, land where the metric measurement of the dense face does.
TEST(MetricScale, SparsePointsMeasureLikeDenseDepth) {
  const auto cam = camera();
  SemanticOptions o;
  const double unit = 0.5;
  const Eigen::Vector4d box(220, 140, 420, 340);  // a 1.2 m face at 3 m
  std::vector<Eigen::Vector3d> pts;
  for (int y = 150; y < 340; y += 12)
    for (int x = 230; x < 420; x += 12) pts.push_back(cam.unproject(Eigen::Vector2d(x, y)) * (3.0 / unit));
  SemanticOptions sparse = o;
  sparse.measurement = sparse_measurement_options(o);
  // A sparse image's squares face the camera: no axes from face normals.
  EXPECT_TRUE(o.measurement.axes_from_planes);
  EXPECT_FALSE(sparse.measurement.axes_from_planes);
  const cv::Mat d = sparse_depth_image(pts, cam, o.monocular.point_radius, unit);
  const Eigen::Vector3d up(0, -1, 0);
  const auto p = measure_pose_from_depth(d, cam, slam::SE3(), box, up, "cabinet", sparse);
  ASSERT_TRUE(p);
  EXPECT_NEAR(p->pose.translation().x(), 0.0, 0.05);
  EXPECT_NEAR(p->pose.translation().z(), 3.0 + 0.225, 0.05);
  // Too few points in the box: no pose.
  const std::vector<Eigen::Vector3d> few(pts.begin(), pts.begin() + 2);
  EXPECT_FALSE(measure_pose_from_depth(sparse_depth_image(few, cam, 2, unit), cam, slam::SE3(), box, up, "cabinet", sparse));
}

}  // namespace
}  // namespace wardmap::semantics

namespace wardmap::semantics {
namespace {

// The `semantics.monocular` keys load over the defaults; a bad one is named in the error.
TEST(MonocularOptions, LoadFromYamlAndNameABadKey) {
  const auto o = load_semantic_options(YAML::Load("monocular: {scale_classes: [door, vehicle], min_points: 6}"), "s.yaml");
  EXPECT_EQ(o.monocular.scale_classes, (std::set<std::string>{"door", "vehicle"}));
  EXPECT_EQ(o.monocular.min_points, 6);
  const auto message = [](const char* yaml) {
    try {
      load_semantic_options(YAML::Load(yaml), "s.yaml");
    } catch (const std::exception& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_NE(message("monocular: {scale_classes: door}").find("semantics.monocular.scale_classes"), std::string::npos);
  EXPECT_NE(message("monocular: {near_quantile: 2}").find("semantics.monocular.near_quantile"), std::string::npos);
}

}  // namespace
}  // namespace wardmap::semantics
