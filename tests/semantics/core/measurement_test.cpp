// Object pose from depth (Assoc. Eq. 1) on rendered depth of known boxes.
#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include "tests/support/test_camera.h"
#include "semantics/object_measurement.h"
#include "semantics/options.h"
#include "tests/semantics/core/options_error.h"

namespace wardmap::semantics {
namespace {

slam::PinholeCamera camera() { return test::vga_camera(); }

// A measurement switch that is on by default loads off from YAML, and a value that is not a boolean
// is named in the error.
template <typename Get>
void expect_switch_on_by_default(const std::string& key, Get get) {
  EXPECT_TRUE(get(SemanticOptions()));
  EXPECT_FALSE(get(load_semantic_options(YAML::Load("measurement: {" + key + ": false}"), "s.yaml")));
  test::expect_load_error_names("measurement: {" + key + ": sideways}", "semantics.measurement." + key);
}

// Depth of a scene: a wall at z = wall, and an axis-aligned box face (front at z = front) covering
// pixels [x0, x1) x [y0, y1). Camera at the origin looking along +z (y down), world = camera frame.
cv::Mat scene(double wall, double front, int x0, int x1, int y0, int y1) {
  cv::Mat d(480, 640, CV_32F, cv::Scalar(wall));
  d(cv::Rect(x0, y0, x1 - x0, y1 - y0)).setTo(front);
  return d;
}

// Depth of a scene seen by the test camera (f = 500): a wall at 8 m and a floor kFloor below the
// camera (y down), world = camera frame.
constexpr double kFloor = 1.2;
cv::Mat floor_scene() {
  cv::Mat d(480, 640, CV_32F, cv::Scalar(8.0f));
  for (int v = 0; v < 480; ++v) {
    const double b = (v - 239.5) / 500.0;
    if (b > 0 && kFloor / b < 8) d.row(v).setTo(static_cast<float>(kFloor / b));
  }
  return d;
}

// A face parallel to the image at depth z over x in [x0, x1] and y (down) in [y0, y1], metres, in
// front of what the scene shows there.
void add_face(cv::Mat& d, double z, double x0, double x1, double y0, double y1) {
  for (int v = 0; v < d.rows; ++v)
    for (int u = 0; u < d.cols; ++u) {
      const double x = (u - 319.5) / 500.0 * z, y = (v - 239.5) / 500.0 * z;
      if (x >= x0 && x <= x1 && y >= y0 && y <= y1) d.at<float>(v, u) = static_cast<float>(z);
    }
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
  // Up of the object is the world's up.
  EXPECT_NEAR(p->pose.rotation_matrix().col(2).dot(up), 1.0, 1e-9);
  // Height: the 5-95 % extent of the trimmed face (1.2 m less 2 x 20 %, less the 10 % tails), 0.65 m,
  // less than the cabinet's 0.8 m: the box gets the class's height and width at least
  // (solid_class_size_floor), the centre stays.
  EXPECT_NEAR(p->size.z(), 0.8, 1e-9);
  EXPECT_NEAR(p->size.x(), 1.2 * 0.6 * 0.9, 0.05);  // wider than the cabinet's 0.45 m
  o.measurement.solid_class_size_floor = false;
  const auto seen = measure_pose_from_depth(d, camera(), T, Eigen::Vector4d(220, 140, 420, 340), up, "cabinet", o);
  ASSERT_TRUE(seen);
  EXPECT_NEAR(seen->size.z(), 1.2 * 0.6 * 0.9, 0.05);
  EXPECT_NEAR((seen->pose.translation() - p->pose.translation()).norm(), 0.0, 1e-9);
  // A narrower face than the class's gets the class's width.
  const cv::Mat narrow = scene(6.0, 3.0, 300, 340, 140, 340);  // 0.24 m wide
  o.measurement.solid_class_size_floor = true;
  const auto slim = measure_pose_from_depth(narrow, camera(), T, Eigen::Vector4d(300, 140, 340, 340), up, "cabinet", o);
  ASSERT_TRUE(slim);
  EXPECT_NEAR(slim->size.x(), 0.45, 1e-9);
  expect_switch_on_by_default("solid_class_size_floor",
                              [](const SemanticOptions& s) { return s.measurement.solid_class_size_floor; });
}

TEST(Measurement, NoPoseForDegenerateInput) {
  SemanticOptions o;
  const Eigen::Vector3d up(0, -1, 0);
  cv::Mat empty(480, 640, CV_32F, cv::Scalar(0));
  EXPECT_FALSE(measure_pose_from_depth(empty, camera(), slam::SE3(), Eigen::Vector4d(200, 100, 400, 300), up, "door", o));
  EXPECT_FALSE(measure_pose_from_depth(cv::Mat(), camera(), slam::SE3(), Eigen::Vector4d(200, 100, 400, 300), up, "door", o));
  const cv::Mat d = scene(5, 2, 0, 100, 100, 300);
  // Cut off by the left border, with side cuts not completed.
  SemanticOptions no_side = o;
  no_side.measurement.complete_side_cuts = false;
  EXPECT_FALSE(measure_pose_from_depth(d, camera(), slam::SE3(), Eigen::Vector4d(0, 100, 100, 300), up, "door", no_side));
  // Cut off by both side borders.
  const cv::Mat wide = scene(5, 2, 0, 640, 100, 300);
  EXPECT_FALSE(measure_pose_from_depth(wide, camera(), slam::SE3(), Eigen::Vector4d(0, 100, 639, 300), up, "door", o));
  // A sliver of a box (a door seen edge-on far away).
  const cv::Mat sliver = scene(5, 2, 300, 306, 100, 300);
  EXPECT_FALSE(measure_pose_from_depth(sliver, camera(), slam::SE3(), Eigen::Vector4d(300, 100, 306, 300), up, "door", o));
  // Cut off at the bottom, but with no class height to complete it from.
  const cv::Mat low = scene(5, 2, 200, 300, 300, 480);
  EXPECT_FALSE(measure_pose_from_depth(low, camera(), slam::SE3(), Eigen::Vector4d(200, 300, 300, 479), up, "bin", o));
  // Cut off at both the top and the bottom.
  const cv::Mat tall = scene(5, 2, 200, 300, 0, 480);
  EXPECT_FALSE(measure_pose_from_depth(tall, camera(), slam::SE3(), Eigen::Vector4d(200, 0, 300, 479), up, "door", o));
  // A 3x3 pixel box.
  EXPECT_FALSE(measure_pose_from_depth(d, camera(), slam::SE3(), Eigen::Vector4d(300, 200, 303, 203), up, "door", o));
}

// A door on the left wall (x = -1 m) of a corridor seen along it, spanning z in [1.5, 2.4] and
// y in [-0.5, 0.5]: its near part lies beyond the image's left border.
TEST(Measurement, SideCutBoxIsCompletedAlongItsFace) {
  SemanticOptions o;
  const Eigen::Vector3d up(0, -1, 0);
  const slam::PinholeCamera c = camera();
  cv::Mat d(480, 640, CV_32F, cv::Scalar(6.0));
  for (int v = 0; v < d.rows; ++v)
    for (int u = 0; u < d.cols; ++u) {
      const double rx = (u - c.cx) / c.fx;
      if (rx < -1.0 / 6.0) d.at<float>(v, u) = static_cast<float>(-1.0 / rx);  // the wall x = -1
    }
  // The door's box: from the border to its far end (z = 2.4), rows of its near end at the border.
  const double u_far = c.cx - c.fx / 2.4, z_border = 1.0 / (c.cx / c.fx);
  const Eigen::Vector4d box(0, c.cy - c.fy * 0.5 / z_border, u_far, c.cy + c.fy * 0.5 / z_border);
  const auto p = measure_pose_from_depth(d, c, slam::SE3(), box, up, "door", o);
  ASSERT_TRUE(p);
  // Completed to the door's 0.9 m width from its seen far end: centre z = 1.95, on the wall.
  EXPECT_NEAR(p->pose.translation().z(), 1.95, 0.03) << p->pose.translation().transpose();
  EXPECT_NEAR(p->pose.translation().x(), -1.0, 0.06);
  EXPECT_NEAR(p->size.x(), 0.9, 1e-9);  // the door's width
  EXPECT_NEAR(std::abs(p->pose.rotation_matrix().col(0).z()), 1.0, 0.02);  // the face runs along z
  // Without the completion its centre would be the seen part's (z about 2.0 - 2.1 here) and no
  // side cut would be placed at all.
  SemanticOptions no_side = o;
  no_side.measurement.complete_side_cuts = false;
  EXPECT_FALSE(measure_pose_from_depth(d, c, slam::SE3(), box, up, "door", no_side));
  // A thin class shows no face to follow: no pose.
  EXPECT_FALSE(measure_pose_from_depth(d, c, slam::SE3(), box, up, "chair", o));
}

TEST(Measurement, NearerOverlappingDetectionIsLeftOut) {
  SemanticOptions o;
  o.measurement.complete_depth_with_class_size = false;
  const Eigen::Vector3d up(0, -1, 0);
  // Far object [200, 400) at 5 m, partly hidden by a near one [320, 440) at 2 m that reaches lower.
  cv::Mat d = scene(8.0, 5.0, 200, 400, 150, 300);
  d(cv::Rect(320, 200, 120, 150)).setTo(2.0);
  const std::vector<Eigen::Vector4d> boxes = {Eigen::Vector4d(200, 150, 400, 300), Eigen::Vector4d(320, 200, 440, 350)};
  const auto occ = nearer_overlapping_detections(d, boxes, o.measurement);
  ASSERT_EQ(occ[0], std::vector<int>{1});
  EXPECT_TRUE(occ[1].empty());
  const auto p = measure_pose_from_depth(d, camera(), slam::SE3(), boxes[0], up, "chair", o, {{boxes[1], std::nullopt}});
  ASSERT_TRUE(p);
  EXPECT_NEAR(p->pose.translation().z(), 5.0, 0.05);
}

// Two cabinets one behind the other, the far one wholly hidden, its detection box the near one's
// give or take a few pixels: neither box is clearly nearer, so each is measured on the near face.
// One place cannot hold both objects, and which is which is unknown: neither keeps a pose.
TEST(Measurement, DetectionsMeasuredAtOnePlaceLoseTheirPoses) {
  SemanticOptions o;
  const Eigen::Vector3d up(0, -1, 0);
  const cv::Mat d = scene(8.0, 3.0, 280, 360, 200, 300);
  const std::vector<Eigen::Vector4d> boxes = {Eigen::Vector4d(280, 200, 360, 300), Eigen::Vector4d(283, 198, 362, 302)};
  const std::vector<std::string> labels = {"cabinet", "cabinet"};
  o.measurement.coincident_ratio = 0;  // off: both are placed on the near face
  auto poses = measure_keyframe_poses(d, camera(), slam::SE3(), boxes, labels, up, o);
  ASSERT_TRUE(poses[0] && poses[1]);
  EXPECT_LT((poses[0]->pose.translation() - poses[1]->pose.translation()).norm(), 0.05);
  o.measurement.coincident_ratio = 0.5;
  poses = measure_keyframe_poses(d, camera(), slam::SE3(), boxes, labels, up, o);
  EXPECT_FALSE(poses[0]);
  EXPECT_FALSE(poses[1]);
}

// The footprint decides when it can: the box ending clearly higher is the farther object's.
TEST(Measurement, CoincidentPosesKeepTheClearlyNearerOne) {
  SemanticOptions o;
  const Eigen::Vector3d up(0, -1, 0);
  const ObjectPose here{slam::SE3(Eigen::Matrix3d::Identity(), Eigen::Vector3d(0, 0, 3)), Eigen::Vector3d(0.5, 0.5, 0.9)};
  ObjectPose near_here = here, apart = here;
  near_here.pose = slam::SE3(Eigen::Matrix3d::Identity(), Eigen::Vector3d(0.15, 0, 3.1));
  apart.pose = slam::SE3(Eigen::Matrix3d::Identity(), Eigen::Vector3d(0.55, 0, 3));
  const std::vector<std::string> chairs = {"chair", "chair"};
  const auto run = [&](const ObjectPose& b, double bottom_a, double bottom_b, const std::vector<std::string>& labels) {
    std::vector<std::optional<ObjectPose>> poses = {here, b};
    drop_coincident_poses(poses, {Eigen::Vector4d(300, 200, 340, bottom_a), Eigen::Vector4d(302, 200, 342, bottom_b)},
                          labels, up, camera(), slam::SE3(), o);
    return std::make_pair(poses[0].has_value(), poses[1].has_value());
  };
  EXPECT_EQ(run(near_here, 300, 320, chairs), std::make_pair(false, true));  // the second reaches lower
  EXPECT_EQ(run(near_here, 320, 300, chairs), std::make_pair(true, false));
  EXPECT_EQ(run(near_here, 300, 303, chairs), std::make_pair(false, false));  // unknown: neither
  EXPECT_EQ(run(apart, 300, 303, chairs), std::make_pair(true, true));       // two chairs side by side
  // A cup on a table stands where the table is.
  EXPECT_EQ(run(near_here, 300, 303, {"chair", "table"}), std::make_pair(true, true));
}

// Neither box clearly nearer (both end at the image's bottom): the poses' projections judge.
TEST(Measurement, CoincidentPosesJudgedByTheirProjections) {
  SemanticOptions o;
  const Eigen::Vector3d up(0, -1, 0);
  const auto chair_at = [](double x, double z) {
    return ObjectPose{slam::SE3(Eigen::Matrix3d::Identity(), Eigen::Vector3d(x, 0.8, z)), Eigen::Vector3d(0.5, 0.9, 0.5)};
  };
  const auto run = [&](const ObjectPose& a, const ObjectPose& b, const Eigen::Vector4d& box_a, const Eigen::Vector4d& box_b) {
    std::vector<std::optional<ObjectPose>> poses = {a, b};
    drop_coincident_poses(poses, {box_a, box_b}, {"chair", "chair"}, up, camera(), slam::SE3(), o);
    return std::make_pair(poses[0].has_value(), poses[1].has_value());
  };
  const auto box_of = [&](const ObjectPose& p) {
    const auto b = project_box(p, camera(), slam::SE3());
    EXPECT_TRUE(b);
    return b.value_or(Eigen::Vector4d::Zero());
  };
  // Two chairs 0.2 m apart (one of them measured off), each filling its own box: both kept.
  const ObjectPose left = chair_at(-0.1, 3), right = chair_at(0.1, 3);
  EXPECT_EQ(run(left, right, box_of(left), box_of(right)), std::make_pair(true, true));
  // A second box in the corner of the first, both measured on the first's object: only the first
  // keeps its pose, whichever order they come in.
  const Eigen::Vector4d full = box_of(left), corner(full(0) + 0.5 * (full(2) - full(0)), full(1) + 0.4 * (full(3) - full(1)),
                                                    full(2) + 20, full(3));
  const ObjectPose on_it = chair_at(-0.05, 3.05);
  EXPECT_EQ(run(left, on_it, full, corner), std::make_pair(true, false));
  EXPECT_EQ(run(on_it, left, corner, full), std::make_pair(false, true));
  // The key loads; a bad value is named.
  EXPECT_DOUBLE_EQ(
      load_semantic_options(YAML::Load("measurement: {coincident_projection_margin: 0.3}"), "s.yaml").measurement.coincident_projection_margin,
      0.3);
  test::expect_load_error_names("measurement: {coincident_projection_margin: -1}", "measurement.coincident_projection_margin");
  // Off: neither keeps a pose.
  o.measurement.coincident_projection_margin = 2;
  EXPECT_EQ(run(left, right, box_of(left), box_of(right)), std::make_pair(false, false));
  EXPECT_EQ(run(left, on_it, full, corner), std::make_pair(false, false));
}

// A box the camera stands beside (a bed passed close) projects as its part in front of the camera:
// the corners there and where its edges cross 0.1 m, clipped to the image.
TEST(Measurement, ProjectionOfABoxPartlyBehindTheCamera) {
  const slam::PinholeCamera c = camera();
  const auto box_at = [](double z) {
    return ObjectPose{slam::SE3(Eigen::Matrix3d::Identity(), Eigen::Vector3d(1.0, 0.5, z)),
                      Eigen::Vector3d(0.6, 0.4, 2.0)};
  };
  // z from -0.7 to 1.3: its nearest seen corner (x 0.7, y 0.3) at z 1.3, the rest out of the image.
  const auto b = project_box(box_at(0.3), c, slam::SE3());
  ASSERT_TRUE(b);
  EXPECT_NEAR((*b)(0), c.cx + c.fx * 0.7 / 1.3, 1e-9);
  EXPECT_NEAR((*b)(1), c.cy + c.fy * 0.3 / 1.3, 1e-9);
  EXPECT_DOUBLE_EQ((*b)(2), c.width - 1);
  EXPECT_DOUBLE_EQ((*b)(3), c.height - 1);
  EXPECT_FALSE(project_box(box_at(-2.0), c, slam::SE3()));  // wholly behind the camera
  // Wholly in front: the corners' box.
  const auto whole = project_box(box_at(5.0), c, slam::SE3());
  ASSERT_TRUE(whole);
  EXPECT_NEAR((*whole)(0), c.cx + c.fx * 0.7 / 6.0, 1e-9);
  EXPECT_NEAR((*whole)(3), c.cy + c.fy * 0.7 / 4.0, 1e-9);
}

// An iv pole in the box of the two pole tests below (180 rows: 1.8 m at 5 m with f = 500), seen by
// an upright camera at the origin.
std::optional<ObjectPose> measure_pole(const cv::Mat& depth, const SemanticOptions& o) {
  return measure_pose_from_depth(depth, camera(), slam::SE3(), Eigen::Vector4d(300, 150, 340, 330),
                                 Eigen::Vector3d(0, -1, 0), "iv_pole", o);
}

// A pole's box holds few of its pixels; when its depth window lands on the wall far behind, the
// box's height tells: a 1.8 m pole filling 180 rows stands about 5 m away, not 9.
TEST(Measurement, TallClassFartherThanItsBoxHeightAllowsGetsNoPose) {
  SemanticOptions o;
  const cv::Mat wall = scene(9.0, 9.0, 0, 1, 0, 1);
  EXPECT_FALSE(measure_pole(wall, o));
  const auto p = measure_pole(scene(9.0, 5.0, 300, 340, 150, 330), o);
  ASSERT_TRUE(p);
  EXPECT_NEAR(p->pose.translation().z(), 5.0, 0.1);  // a pole (axis class) stands where its shaft is seen
  o.measurement.tall_depth_ratio = 0;  // off: the wall is taken for the pole
  const auto off = measure_pole(wall, o);
  ASSERT_TRUE(off);
  EXPECT_GT(off->pose.translation().z(), 8.9);
}

// A pole beside a bed's foot: the footboard (nearer, across the box's lower rows) fills more of the
// box than the shaft. The pole is placed on its shaft, seen in the box's upper half, not on the
// footboard, and its centre is the shaft's axis, not the seen surface pushed back by half the class.
TEST(Measurement, AxisClassIsPlacedOnItsShaftAboveWhatStandsInFront) {
  SemanticOptions o;
  cv::Mat d(480, 640, CV_32F, cv::Scalar(9.0f));
  d(cv::Rect(316, 150, 8, 180)).setTo(5.0);  // the shaft, 8 px wide
  d(cv::Rect(290, 260, 60, 70)).setTo(4.3);  // the footboard in front of its lower part
  const auto p = measure_pole(d, o);
  ASSERT_TRUE(p);
  EXPECT_NEAR(p->pose.translation().z(), 5.0, 0.05);
  EXPECT_NEAR(p->pose.translation().x(), 0.0, 0.05);
  o.axis_classes.clear();  // measured as a thin class: the nearest window is the footboard's
  const auto front = measure_pole(d, o);
  ASSERT_TRUE(front);
  EXPECT_LT(front->pose.translation().z(), 4.7);
}

// A pole 3 m away with the wall 1.4 m behind it, its box as wide as its base and cut by the bottom
// border (aisle_left_turn_slow_5's iv pole 15 in keyframe 101): the shaft is 7 px wide, 12 % of
// the trimmed box's columns, but the box's samples were 4 px apart, one column of them in 14 fell on
// the shaft (7 %, under measurement.thin_support), and the wall was taken. Every column of a pole's
// box is sampled now.
TEST(Measurement, PoleShaftNarrowerThanTheSampleSpacingIsFound) {
  const SemanticOptions o;
  cv::Mat d(480, 640, CV_32F, cv::Scalar(4.4f));
  d(cv::Rect(430, 112, 7, 368)).setTo(3.05);
  const auto p = measure_pose_from_depth(d, camera(), slam::SE3(), Eigen::Vector4d(407, 112, 499, 480),
                                         Eigen::Vector3d(0, -1, 0), "iv_pole", o);
  ASSERT_TRUE(p);
  EXPECT_NEAR(p->pose.translation().z(), 3.05, 0.1);
}

// A door on a side wall (the plane x = 1 m), seen obliquely down the corridor: it spans z = 3-3.9 m.
// Its width is the axis closer to the line of sight, yet it is its face normal that hides a depth,
// and its ends are where the rays through the box's edges meet the face. So are its top and foot:
// the box's rows are those of its near end (z = 3 m), whose edge column meets the face there; the
// far edge's column meets it beyond both.
TEST(Measurement, ObliqueFlatFaceIsPlacedBetweenItsBoxEdges) {
  SemanticOptions o;
  const Eigen::Vector3d up(0, -1, 0);
  const auto cam = camera();
  cv::Mat d(480, 640, CV_32F, cv::Scalar(0.0f));
  for (int u = 330; u < 640; ++u) d.col(u).setTo(cam.fx / (u - cam.cx));  // z-depth of the wall x = 1
  const double top = -0.85, floor = 1.2;  // the door's top and foot (y down)
  const Eigen::Vector4d box(cam.cx + cam.fx / 3.9, cam.cy + cam.fy * top / 3.0, cam.cx + cam.fx / 3.0,
                            cam.cy + cam.fy * floor / 3.0);
  const auto p = measure_pose_from_depth(d, cam, slam::SE3(), box, up, "door", o);
  ASSERT_TRUE(p);
  EXPECT_NEAR(p->pose.translation().z(), 3.45, 0.03);
  EXPECT_NEAR(p->pose.translation().x(), 1.0 + 0.03, 0.02);  // pushed back by half the door's 0.06
  EXPECT_NEAR(p->size.x(), 0.9, 0.05);
  EXPECT_NEAR(p->size.z(), 2.05, 0.03);                 // top -0.85 to foot 1.2
  EXPECT_NEAR(p->pose.translation().y(), 0.175, 0.02);  // their middle
  o.measurement.flat_height_from_box_rows = false;      // the trimmed points' 5-95 %: about half of it
  const auto points_only = measure_pose_from_depth(d, cam, slam::SE3(), box, up, "door", o);
  ASSERT_TRUE(points_only);
  EXPECT_LT(points_only->size.z(), 1.4);
  EXPECT_FALSE(load_semantic_options(YAML::Load("measurement: {flat_height_from_box_rows: false}"), "s.yaml")
                   .measurement.flat_height_from_box_rows);
  test::expect_load_error_names("measurement: {flat_height_from_box_rows: tall}",
                                "semantics.measurement.flat_height_from_box_rows");
  o.measurement.flat_height_from_box_rows = true;
  o.measurement.flat_ratio = 0;  // off: the width is taken for the hidden depth
  const auto off = measure_pose_from_depth(d, cam, slam::SE3(), box, up, "door", o);
  ASSERT_TRUE(off);
  EXPECT_GT(off->pose.translation().z(), 3.5);
  EXPECT_DOUBLE_EQ(load_semantic_options(YAML::Load("measurement: {flat_ratio: 0.1}"), "s.yaml").measurement.flat_ratio,
                   0.1);
  test::expect_load_error_names("measurement: {flat_ratio: 1.5}", "semantics.measurement.flat_ratio");
}

// A cabinet behind a bed, seen beside it: the bed's box holds the cabinet's, yet only the bed's own
// pixels (inside its measured 3-D box) are left out, so the cabinet keeps a pose.
TEST(Measurement, MeasuredOccluderHidesOnlyItsOwnPixels) {
  SemanticOptions o;
  o.measurement.complete_depth_with_class_size = false;
  const Eigen::Vector3d up(0, -1, 0);
  // Wall at 7 m; cabinet face at 4 m over [360, 440) x [220, 300); bed face at 3 m over
  // [160, 380) x [200, 400), hiding the cabinet's left quarter. The bed's box reaches u = 440 (its
  // far end, not drawn here), so it holds the whole cabinet box.
  cv::Mat d = scene(7.0, 4.0, 360, 440, 220, 300);
  d(cv::Rect(160, 200, 220, 200)).setTo(3.0);
  const std::vector<Eigen::Vector4d> boxes = {Eigen::Vector4d(160, 200, 440, 400), Eigen::Vector4d(360, 220, 440, 300)};
  const auto poses = measure_keyframe_poses(d, camera(), slam::SE3(), boxes, {"box", "cabinet"}, up, o);
  ASSERT_TRUE(poses[0]);
  ASSERT_TRUE(poses[1]);
  EXPECT_NEAR(poses[0]->pose.translation().z(), 3.0, 0.05);
  EXPECT_NEAR(poses[1]->pose.translation().z(), 4.0, 0.05);
  // Only the visible part right of the bed (u >= 380) is the cabinet's.
  EXPECT_GT(poses[1]->pose.translation().x(), (380 - 319.5) / 500.0 * 4.0);
  // Were the bed not measured, its whole box would hide the cabinet: no pose rather than a wrong one.
  EXPECT_FALSE(measure_pose_from_depth(d, camera(), slam::SE3(), boxes[1], up, "cabinet", o, {{boxes[0], std::nullopt}}));
}

// Pixels inside a measured occluder's image box that lie outside its inflated 3-D box (a part its
// measurement missed) but no deeper than that box's far end are the occluder's too, with
// mask_to_far_end: the far cabinet is then measured on its own face, not on that part.
TEST(Measurement, FarEndMaskHidesAnOccludersPixelsOutsideItsMeasuredBox) {
  SemanticOptions o;
  const Eigen::Vector3d up(0, -1, 0);
  // Far cabinet face at 4 m over [200, 295); the near one's unmeasured part at 3.3 m over [295, 340).
  cv::Mat d = scene(8.0, 4.0, 200, 295, 200, 320);
  d(cv::Rect(295, 200, 45, 120)).setTo(3.3);
  const Eigen::Vector4d far_box(260, 200, 340, 320), near_box(290, 200, 420, 330);
  // The near cabinet as measured: centred 0.5 m right at 3.2 m, so its inflated box spans x 0.2-0.8 m
  // and depths up to 3.525 m; the 3.3 m part lies left of it (x < 0.13 m).
  const ObjectPose near{slam::SE3(Eigen::Matrix3d::Identity(), Eigen::Vector3d(0.5, 0, 3.2)), Eigen::Vector3d(0.4, 0.8, 0.45)};
  // The far cabinet's measured depth (its centre, 0.225 m behind its front) with one occluder.
  const auto measured_z = [&](const std::string& far_end, bool same_class) {
    o.measurement.mask_to_far_end = far_end;
    const auto p = measure_pose_from_depth(d, camera(), slam::SE3(), far_box, up, "cabinet", o,
                                           {Occluder{near_box, near, same_class}});
    return p ? p->pose.translation().z() : -1.0;
  };
  EXPECT_NEAR(measured_z("none", true), 3.3 + 0.225, 0.05);  // on the near cabinet's part
  EXPECT_NEAR(measured_z("same_class", true), 4.0 + 0.225, 0.05);
  // An occluder of another class is masked only by its 3-D box under same_class, by its far end under all.
  EXPECT_NEAR(measured_z("same_class", false), 3.3 + 0.225, 0.05);
  EXPECT_NEAR(measured_z("all", false), 4.0 + 0.225, 0.05);
}

// The key loads over the default; an unknown value is named in the error.
TEST(Measurement, FarEndMaskKeyLoadsAndABadValueIsNamed) {
  EXPECT_EQ(SemanticOptions().measurement.mask_to_far_end, "none");
  const auto o = load_semantic_options(YAML::Load("measurement: {mask_to_far_end: all}"), "s.yaml");
  EXPECT_EQ(o.measurement.mask_to_far_end, "all");
  test::expect_load_error_names("measurement: {mask_to_far_end: near}", "semantics.measurement.mask_to_far_end");
}

// A chair's back detected again inside the whole chair's box (7-Scenes: YOLOX finds both). The back
// is slats at 2 m, 14 rows of each 20 (70 %), with the wall at 4 m between them. The whole chair is
// nearer (its box reaches lower), so it is measured first and its 3-D box hides the slats: what is
// left of the back's box is the wall, 2 m behind the chair. That is the chair seen through: the back
// gets no pose and is marked a duplicate (the mapper makes no measurement of it). Another object of
// the class standing just behind the chair keeps its pose.
TEST(Measurement, SameClassDetectionSeenThroughANearerOneIsADuplicate) {
  SemanticOptions o;
  o.measurement.complete_depth_with_class_size = false;
  const Eigen::Vector3d up(0, -1, 0);
  const auto chair = [](double behind) {
    cv::Mat d = scene(behind, 2.0, 250, 390, 260, 400);  // seat and legs
    for (int y = 150; y < 260; ++y)
      if ((y - 150) % 20 < 14) d(cv::Rect(250, y, 140, 1)).setTo(2.0);
    return d;
  };
  const std::vector<Eigen::Vector4d> boxes = {Eigen::Vector4d(250, 150, 390, 400), Eigen::Vector4d(250, 190, 390, 270)};
  const std::vector<std::string> labels = {"box", "box"};
  std::vector<bool> duplicates;
  auto poses = measure_keyframe_poses(chair(4.0), camera(), slam::SE3(), boxes, labels, up, o, nullptr, &duplicates);
  ASSERT_TRUE(poses[0]);
  EXPECT_NEAR(poses[0]->pose.translation().z(), 2.0, 0.05);
  EXPECT_FALSE(poses[1]);
  EXPECT_EQ(duplicates, std::vector<bool>({false, true}));
  // Another class's box hiding it (a table's) does not make it a duplicate: it is measured behind.
  poses = measure_keyframe_poses(chair(4.0), camera(), slam::SE3(), boxes, {"crate", "box"}, up, o, nullptr, &duplicates);
  ASSERT_TRUE(poses[1]);
  EXPECT_NEAR(poses[1]->pose.translation().z(), 4.0, 0.05);
  EXPECT_EQ(duplicates, std::vector<bool>({false, false}));
  // The chair measured 0.5 m deep (its box ends at 2.6 m with occluder_inflate): what is left beginning
  // within half the class's depth (depth_band 0.6 m for a class without a size) behind it is another
  // object hidden behind it, placed; farther, the background seen through it.
  const ObjectPose deep{slam::SE3(upright_rotation(up, Eigen::Vector3d::UnitX()), Eigen::Vector3d(0, 0.142, 2.25)),
                        Eigen::Vector3d(0.56, 0.5, 1.0)};
  const auto behind = [&](double z) {
    const auto p = measure_pose_from_depth(chair(z), camera(), slam::SE3(), boxes[1], up, "box", o,
                                           {Occluder{boxes[0], deep, true}});
    return p ? p->pose.translation().z() : -1.0;
  };
  EXPECT_NEAR(behind(2.8), 2.8, 0.05);
  EXPECT_EQ(behind(3.0), -1.0);
  // The chair's image box must hold the back's (duplicate_containment): a box sticking out of it is
  // another object (a wheelchair far behind another shows above it).
  o.measurement.duplicate_containment = 1.0;
  const std::vector<Eigen::Vector4d> wider = {boxes[0], Eigen::Vector4d(250, 190, 391, 270)};
  poses = measure_keyframe_poses(chair(4.0), camera(), slam::SE3(), wider, labels, up, o, nullptr, &duplicates);
  ASSERT_TRUE(poses[1]);
  EXPECT_NEAR(poses[1]->pose.translation().z(), 4.0, 0.05);
  EXPECT_EQ(duplicates, std::vector<bool>({false, false}));
  o.measurement.duplicate_containment = 0.8;
  // What is left must be one surface (duplicate_rest_window_share): with another object at 3 m behind
  // two thirds of the slats' gaps and the wall at 4 m behind the rest, it is an object hidden behind
  // the chair, measured on that object; with the key at 0, a duplicate again.
  cv::Mat two_depths = chair(4.0);
  for (int y = 190; y < 270; ++y)
    if ((y - 150) % 20 >= 14) two_depths(cv::Rect(250, y, 93, 1)).setTo(3.0);
  poses = measure_keyframe_poses(two_depths, camera(), slam::SE3(), boxes, labels, up, o, nullptr, &duplicates);
  ASSERT_TRUE(poses[1]);
  EXPECT_NEAR(poses[1]->pose.translation().z(), 3.0, 0.1);
  EXPECT_EQ(duplicates, std::vector<bool>({false, false}));
  o.measurement.duplicate_rest_window_share = 0;
  poses = measure_keyframe_poses(two_depths, camera(), slam::SE3(), boxes, labels, up, o, nullptr, &duplicates);
  EXPECT_FALSE(poses[1]);
  EXPECT_EQ(duplicates, std::vector<bool>({false, true}));
  o.measurement.duplicate_rest_window_share = 0.8;
  // Off: placed on the wall.
  o.measurement.max_inside_same_class_share = 2;
  poses = measure_keyframe_poses(chair(4.0), camera(), slam::SE3(), boxes, labels, up, o, nullptr, &duplicates);
  ASSERT_TRUE(poses[1]);
  EXPECT_NEAR(poses[1]->pose.translation().z(), 4.0, 0.05);
  EXPECT_EQ(duplicates, std::vector<bool>({false, false}));
  EXPECT_DOUBLE_EQ(SemanticOptions().measurement.max_inside_same_class_share, 0.5);
  EXPECT_DOUBLE_EQ(load_semantic_options(YAML::Load("measurement: {max_inside_same_class_share: 0.7}"), "s.yaml")
                       .measurement.max_inside_same_class_share,
                   0.7);
  test::expect_load_error_names("measurement: {max_inside_same_class_share: -1}",
                                "semantics.measurement.max_inside_same_class_share");
  test::expect_load_error_names("measurement: {duplicate_containment: 1.5}", "semantics.measurement.duplicate_containment");
  test::expect_load_error_names("measurement: {duplicate_rest_window_share: 1.5}",
                                "semantics.measurement.duplicate_rest_window_share");
}

// A pole (a box-masked class: an open frame) stands in front of a cabinet, its shaft at 2.5 m and
// its image box (spokes, hook) over the cabinet's right half. With box_mask_to_far_end the cabinet
// shows between the spokes and beside the shaft and is measured on its whole face; otherwise the
// pole's whole image box hides that half.
TEST(Measurement, BoxMaskedOccluderHidesItsBoxOnlyUpToItsFarEnd) {
  SemanticOptions o;
  const Eigen::Vector3d up(0, -1, 0);
  // Wall at 8 m; cabinet face at 4 m over [200, 440) x [200, 320) (x -0.96 to 0.96 m); the shaft at
  // 2.5 m over [364, 376).
  cv::Mat d = scene(8.0, 4.0, 200, 440, 200, 320);
  d(cv::Rect(364, 100, 12, 300)).setTo(2.5);
  const Eigen::Vector4d cabinet_box(200, 200, 440, 320), pole_box(300, 100, 440, 400);
  // The pole as measured: its axis at the shaft (x = 0.4 m), 0.5 m wide and deep, so its inflated
  // box ends at 3.05 m.
  const ObjectPose pole{slam::SE3(Eigen::Matrix3d::Identity(), Eigen::Vector3d(0.4, 0, 2.5)), Eigen::Vector3d(0.5, 1.8, 0.5)};
  const auto measured = [&](bool to_far_end) {
    o.measurement.box_mask_to_far_end = to_far_end;
    return measure_pose_from_depth(d, camera(), slam::SE3(), cabinet_box, up, "cabinet", o,
                                   {Occluder{pole_box, pole, false, true}});
  };
  const auto whole_face = measured(true);
  ASSERT_TRUE(whole_face);
  EXPECT_NEAR(whole_face->pose.translation().x(), 0.0, 0.05);
  EXPECT_NEAR(whole_face->pose.translation().z(), 4.0 + 0.225, 0.05);
  // Only the columns left of the pole's box (u < 300) are left: the centre moves left.
  const auto left_part = measured(false);
  ASSERT_TRUE(left_part);
  EXPECT_LT(left_part->pose.translation().x(), -0.3);
  // Unmeasured, the pole hides its whole image box either way.
  o.measurement.box_mask_to_far_end = true;
  const auto unmeasured = measure_pose_from_depth(d, camera(), slam::SE3(), cabinet_box, up, "cabinet", o,
                                                  {Occluder{pole_box, std::nullopt, false, true}});
  ASSERT_TRUE(unmeasured);
  EXPECT_LT(unmeasured->pose.translation().x(), -0.3);
  expect_switch_on_by_default("box_mask_to_far_end",
                              [](const SemanticOptions& s) { return s.measurement.box_mask_to_far_end; });
}

// A wheelchair seen from the front: its seat and armrests a face at 4 m, 0.3-0.9 m below the camera;
// its footplate 0.4 m nearer, on the floor 1.2 m below the camera, in the rows box_shrink trims. With
// front_from_foot its front is where the box's bottom row meets the floor below the box.
TEST(Measurement, FrontFromTheFootOfALowFrontedClass) {
  SemanticOptions o;
  const Eigen::Vector3d up(0, -1, 0);
  cv::Mat d = floor_scene();
  add_face(d, 4.0, -0.3, 0.3, 0.3, 0.9);
  add_face(d, 3.6, -0.2, 0.2, 1.0, kFloor);
  const Eigen::Vector4d box(282, 277, 357, 406);  // bottom: the footplate's foot, 239.5 + 500 * 1.2 / 3.6
  const auto centre_z = [&]() {
    const auto p = measure_pose_from_depth(d, camera(), slam::SE3(), box, up, "wheelchair", o);
    return p ? p->pose.translation().z() : -1.0;
  };
  // The wheelchair's 1 m depth behind its front: 3.6 + 0.5 from the foot, 4.0 + 0.5 from the points.
  EXPECT_NEAR(centre_z(), 4.1, 0.03);
  o.measurement.front_from_foot = false;
  EXPECT_NEAR(centre_z(), 4.5, 0.03);
  // Not a floor below the box (something 0.2 m above it on its left half): the points' front.
  o.measurement.front_from_foot = true;
  d(cv::Rect(200, 409, 120, 20)).setTo(2.9f);
  EXPECT_NEAR(centre_z(), 4.5, 0.03);
  // Other classes keep the points' front.
  EXPECT_TRUE(SemanticOptions().foot_front_classes.count("wheelchair"));
  EXPECT_FALSE(SemanticOptions().foot_front_classes.count("chair"));
  expect_switch_on_by_default("front_from_foot", [](const SemanticOptions& s) { return s.measurement.front_from_foot; });
  EXPECT_DOUBLE_EQ(load_semantic_options(YAML::Load("measurement: {floor_spread: 0.1}"), "s.yaml").measurement.floor_spread,
                   0.1);
  test::expect_load_error_names("measurement: {floor_spread: -1}", "semantics.measurement.floor_spread");
}

// Options with the foot window on, at the value measured (measurement.foot_window_rows 0.06).
SemanticOptions foot_window_options() {
  SemanticOptions o;
  o.measurement.foot_window_rows = 0.06;
  return o;
}

// A chair's face 0.5 m wide at 5 m, standing on the floor scene's floor from 0.35 m below the camera.
cv::Mat chair_on_the_floor_scene() {
  cv::Mat d = floor_scene();
  add_face(d, 5.0, -0.25, 0.25, 0.35, kFloor);
  return d;
}

// A chair of a row seen end on, behind a missed one: its face at 5 m stands on the floor 1.2 m below
// the camera, and the missed chair's seat and back, a slab at 4.4 m floating 0.3-0.75 m below the
// camera, hide most of its box. The fullest window is the slab; with foot_window_rows the window must
// begin where the box's bottom row meets the floor just below it (5 m), and the chair is measured.
TEST(Measurement, AStandingClassIsMeasuredWhereItsFootMeetsTheFloor) {
  const SemanticOptions o = foot_window_options();
  const Eigen::Vector3d up(0, -1, 0);
  cv::Mat d = chair_on_the_floor_scene();
  add_face(d, 4.4, -0.3, 0.3, 0.3, 0.75);
  const Eigen::Vector4d box(269.5, 274.5, 369.5, 359.5);  // the chair's face; bottom row: its foot at 5 m
  const auto centre_z = [&](const SemanticOptions& s) {
    const auto p = measure_pose_from_depth(d, camera(), slam::SE3(), box, up, "chair", s);
    return p ? p->pose.translation().z() : -1.0;
  };
  // The chair's 0.5 m depth behind its face.
  EXPECT_NEAR(centre_z(o), 5.25, 0.03);
  // Off by default.
  EXPECT_DOUBLE_EQ(SemanticOptions().measurement.foot_window_rows, 0);
  EXPECT_NEAR(centre_z(SemanticOptions()), 4.65, 0.03);
  // A class not in foot_window_classes keeps the fullest window.
  SemanticOptions other = o;
  other.foot_window_classes.clear();
  EXPECT_NEAR(centre_z(other), 4.65, 0.03);
  // A box shorter than foot_min_height_share of the class standing on that floor (a chair's back seen
  // above a table, the table's top under it) is not all of the object: the fullest window.
  SemanticOptions tall = o;
  tall.measurement.foot_min_height_share = 1.5;
  EXPECT_NEAR(centre_z(tall), 4.65, 0.03);
  // Something other than a floor under the whole box (a box on a shelf 0.2 m above the floor): no
  // foot, the fullest window.
  cv::Mat shelf = d.clone();
  shelf(cv::Rect(260, 362, 120, 20)).setTo(4.2f);
  d = shelf;
  EXPECT_NEAR(centre_z(o), 4.65, 0.03);
  EXPECT_DOUBLE_EQ(
      load_semantic_options(YAML::Load("measurement: {foot_window_rows: 0.1}"), "s.yaml").measurement.foot_window_rows,
      0.1);
  const std::pair<std::string, std::string> bad_values[] = {{"foot_window_rows", "-1"},
                                                            {"foot_window_slack", "-1"},
                                                            {"foot_floor_share", "2"},
                                                            {"foot_min_height_share", "-1"}};
  for (const auto& [key, value] : bad_values)
    test::expect_load_error_names("measurement: {" + key + ": " + value + "}", "semantics.measurement." + key);
}

// The same chair behind a missed one that stands on the floor in front of its left third: the floor
// below the chair's box shows only beside it, so the box has no floor of its own; measured with the
// keyframe's other detections (a cabinet whose floor shows), it gets the keyframe's floor there.
TEST(Measurement, AStandingClassBehindAMissedOneTakesTheKeyframesFloor) {
  SemanticOptions o = foot_window_options();
  const Eigen::Vector3d up(0, -1, 0);
  cv::Mat d = chair_on_the_floor_scene();
  add_face(d, 4.4, -0.3, 0.0, 0.3, kFloor);
  add_face(d, 4.0, 1.0, 1.5, 0.4, kFloor);
  const Eigen::Vector4d chair(269.5, 274.5, 369.5, 359.5), cabinet(444.5, 289.5, 507, 389.5);
  const auto poses = measure_keyframe_poses(d, camera(), slam::SE3(), {chair, cabinet}, {"chair", "cabinet"}, up, o);
  ASSERT_TRUE(poses[0]);
  EXPECT_NEAR(poses[0]->pose.translation().z(), 5.25, 0.03);
  // Alone, the box shows no floor of its own: the fullest window, the missed chair's.
  const auto alone = measure_pose_from_depth(d, camera(), slam::SE3(), chair, up, "chair", o);
  ASSERT_TRUE(alone);
  EXPECT_LT(alone->pose.translation().z(), 4.8);
  // Required on fewer of the pixels below the box than lie on that floor: the fullest window again.
  o.measurement.foot_floor_share = 0.9;
  const auto strict = measure_keyframe_poses(d, camera(), slam::SE3(), {chair, cabinet}, {"chair", "cabinet"}, up, o);
  ASSERT_TRUE(strict[0]);
  EXPECT_LT(strict[0]->pose.translation().z(), 4.8);
}

// A door cut by the image's bottom border is completed from its class height: its top is real, the
// rest comes from the door's 2.05 m.
TEST(Measurement, BottomCutBoxIsCompletedFromTheClassHeight) {
  SemanticOptions o;
  const Eigen::Vector3d up(0, -1, 0);
  // Door face at z = 3 m over x in [-0.6, 0.3], y (down) in [-0.5, 1.55]: with f = 500 it spans
  // u in [219.5, 369.5] and v in [156, 498], so the image cuts it at the bottom.
  const auto pixel = [](double metres, double c) { return c + metres / 3.0 * 500.0; };
  const int u0 = static_cast<int>(pixel(-0.6, 319.5)), u1 = static_cast<int>(pixel(0.3, 319.5));
  const int v0 = static_cast<int>(pixel(-0.5, 239.5));
  const cv::Mat d = scene(8.0, 3.0, u0, u1, v0, 480);
  const Eigen::Vector4d box(u0, v0, u1, 479);
  const auto p = measure_pose_from_depth(d, camera(), slam::SE3(), box, up, "door", o);
  ASSERT_TRUE(p);
  // True centre: x = -0.15, y = 0.525, and z = 3 + 0.03 (half of the door class's 0.06 m
  // thickness, completed behind the face).
  EXPECT_NEAR(p->pose.translation().x(), -0.15, 0.03);
  EXPECT_NEAR(p->pose.translation().y(), 0.525, 0.04);
  EXPECT_NEAR(p->pose.translation().z(), 3.03, 0.02);
  EXPECT_NEAR(p->size.z(), 2.05, 0.02);
}

// A bed seen from above as the camera passes close: a mattress 0.9 m below the camera from z = 1.5
// to 3.5 m, 1 m wide, a headboard at z = 3.5, the floor 1.9 m below the camera. Rows from
// `mattress_to` down show the floor instead of the mattress.
cv::Mat bed_from_above(int mattress_to = 480) {
  const double f = 500, top = 0.9, floor = 1.9;
  cv::Mat d(480, 640, CV_32F, cv::Scalar(8.0f));
  for (int v = 0; v < 480; ++v)
    for (int u = 0; u < 640; ++u) {
      const double a = (u - 319.5) / f, b = (v - 239.5) / f;
      if (b * 3.5 >= 0.5 && b * 3.5 <= top && std::abs(a * 3.5) <= 0.5) d.at<float>(v, u) = 3.5f;
      if (b <= 0) continue;
      if (v >= mattress_to) {
        d.at<float>(v, u) = static_cast<float>(floor / b);
        continue;
      }
      const double z = top / b;  // the mattress plane y = top
      if (z >= 1.5 && z <= 3.5 && std::abs(a * z) <= 0.5) d.at<float>(v, u) = static_cast<float>(z);
    }
  return d;
}

// The image's bottom border cuts the bed's top surface, hiding its near end (not its lower part):
// its length and centre are unknown, so no pose. Without the rule (bottom_face_band 0) the cut is
// completed downwards and the bed gets a pose.
TEST(Measurement, BottomCutTopSurfaceGetsNoPose) {
  SemanticOptions o;
  o.measurement.bottom_face_band = 0.3;
  const Eigen::Vector3d up(0, -1, 0);
  const cv::Mat d = bed_from_above();
  // At the bottom row the mattress is 1.88 m away: its sides at u = 319.5 -/+ 133.
  const Eigen::Vector4d box(186, 311, 453, 479);
  EXPECT_FALSE(measure_pose_from_depth(d, camera(), slam::SE3(), box, up, "bed", o));
  o.measurement.bottom_face_band = 0;
  EXPECT_TRUE(measure_pose_from_depth(d, camera(), slam::SE3(), box, up, "bed", o));
}

// A support without a pose (the bed above, cut by the bottom border) holding a small box it reaches
// lower than: its whole box would hide what stands on it. It hides nothing when the small box shows
// nothing in front of its own depth, and its whole box again when something does (a footboard).
TEST(Measurement, UnplacedSupportHidesWhatStandsOnItOnlyWhenInFront) {
  SemanticOptions o;
  o.measurement.bottom_face_band = 0.3;
  o.measurement.complete_depth_with_class_size = false;
  const Eigen::Vector3d up(0, -1, 0);
  cv::Mat d = bed_from_above();
  // A 10 cm cube on the mattress's far end, 3.3 m away (u 312-327, v 361-376), farther than most
  // of the bed: the bed is the nearer one by depth too (the support rule of
  // nearer_overlapping_detections spares only a support that is not).
  d(cv::Rect(312, 361, 16, 16)).setTo(3.25f);
  const Eigen::Vector4d bed(186, 311, 453, 479), cube(311, 360, 329, 378);
  ASSERT_EQ(nearer_overlapping_detections(d, {bed, cube}, o.measurement, {true, false})[1], std::vector<int>{0});
  const std::vector<std::string> labels = {"bed", "box"};
  EXPECT_LE(box_front_share(d, cube, o.measurement), o.measurement.support_front_share);
  auto poses = measure_keyframe_poses(d, camera(), slam::SE3(), {bed, cube}, labels, up, o);
  EXPECT_FALSE(poses[0]);
  ASSERT_TRUE(poses[1]);
  EXPECT_NEAR(poses[1]->pose.translation().z(), 3.3, 0.1);
  EXPECT_NEAR(poses[1]->pose.translation().x(), 0.0, 0.05);
  // The old rule (every unplaced occluder hides its whole box) leaves it without a pose.
  o.measurement.support_front_share = -1;
  EXPECT_FALSE(measure_keyframe_poses(d, camera(), slam::SE3(), {bed, cube}, labels, up, o)[1]);
  // A board 0.5 m in front of the cube's lowest third: the bed hides its whole box again.
  o.measurement.support_front_share = 0.1;
  d(cv::Rect(300, 371, 40, 8)).setTo(2.75f);
  EXPECT_GT(box_front_share(d, cube, o.measurement), o.measurement.support_front_share);
  poses = measure_keyframe_poses(d, camera(), slam::SE3(), {bed, cube}, labels, up, o);
  EXPECT_FALSE(poses[1]);
  EXPECT_DOUBLE_EQ(
      load_semantic_options(YAML::Load("measurement: {support_front_share: 0.3}"), "s.yaml").measurement.support_front_share,
      0.3);
  test::expect_load_error_names("measurement: {support_front_share: 2}", "semantics.measurement.support_front_share");
}

// A chair's back rising 0.15 m above a table's top, behind its far half (7-Scenes: YOLOX's table box
// holds the chair's). The table was measured: its 3-D box spans depths 1.6-2.4 m and heights up to
// its top, 0.30 m below the camera. Inflated by occluder_inflate (0.1 m) upwards too, it would hide
// the back's slats (60 % of the rows, at 2.3 m; the wall at 4 m between them) up to 0.20 m, and the
// chair would be placed on the wall. A support's box reaches only support_top_inflate above its top.
TEST(Measurement, WhatRisesAboveAMeasuredSupportIsNotHiddenByIt) {
  SemanticOptions o;
  o.measurement.complete_depth_with_class_size = false;
  const Eigen::Vector3d up(0, -1, 0);
  cv::Mat d(480, 640, CV_32F, cv::Scalar(4.0));
  for (int v = 272; v < 305; ++v)  // heights 0.15-0.30 m below the camera at 2.3 m
    if ((v - 272) % 5 < 3) d(cv::Rect(250, v, 140, 1)).setTo(2.3);
  const Eigen::Vector4d back(250, 272, 390, 305), table_box(100, 260, 540, 479);
  const ObjectPose table{slam::SE3(upright_rotation(up, Eigen::Vector3d::UnitX()), Eigen::Vector3d(0, 0.35, 2.0)),
                         Eigen::Vector3d(1.2, 0.8, 0.1)};
  const auto depth_of = [&](bool support) {
    Occluder occluder{table_box, table, false, false, support};
    const auto p = measure_pose_from_depth(d, camera(), slam::SE3(), back, up, "box", o, {occluder});
    return p ? p->pose.translation().z() : -1.0;
  };
  EXPECT_NEAR(depth_of(true), 2.3, 0.05);
  EXPECT_NEAR(depth_of(false), 4.0, 0.05);  // any other occluder's box is inflated all round
  o.measurement.support_top_inflate = o.measurement.occluder_inflate;
  EXPECT_NEAR(depth_of(true), 4.0, 0.05);
  EXPECT_DOUBLE_EQ(SemanticOptions().measurement.support_top_inflate, 0.03);
  EXPECT_DOUBLE_EQ(
      load_semantic_options(YAML::Load("measurement: {support_top_inflate: 0.05}"), "s.yaml").measurement.support_top_inflate,
      0.05);
  test::expect_load_error_names("measurement: {support_top_inflate: -0.1}", "semantics.measurement.support_top_inflate");
}

// A detector box ending 9 px short of the border: cut there when the mattress fills the rows below
// it, not when they show the floor (the bed's near end is then in the box).
TEST(Measurement, BoxEndingShortOfTheBorderIsCutWhenTheTopSurfaceContinues) {
  SemanticOptions o;
  o.measurement.bottom_face_band = 0.3;
  const Eigen::Vector3d up(0, -1, 0);
  const Eigen::Vector4d box(186, 311, 453, 470);
  EXPECT_FALSE(measure_pose_from_depth(bed_from_above(), camera(), slam::SE3(), box, up, "bed", o));
  EXPECT_TRUE(measure_pose_from_depth(bed_from_above(471), camera(), slam::SE3(), box, up, "bed", o));
  // Beyond bottom_cut_reach (0.1 of the box's 159 px height) the box is taken as uncut.
  o.measurement.bottom_cut_reach = 0.05;
  EXPECT_TRUE(measure_pose_from_depth(bed_from_above(), camera(), slam::SE3(), box, up, "bed", o));
}

// The rule holds for long classes only: a class whose tops are shorter than bottom_face_min_length
// (here the bed itself, with the limit raised past its 2 m) is completed as before.
TEST(Measurement, TopSurfaceRuleSparesShortClasses) {
  SemanticOptions o;
  o.measurement.bottom_face_band = 0.3;
  o.measurement.bottom_face_min_length = 2.5;
  const Eigen::Vector3d up(0, -1, 0);
  EXPECT_TRUE(measure_pose_from_depth(bed_from_above(), camera(), slam::SE3(), Eigen::Vector4d(186, 311, 453, 479), up,
                                      "bed", o));
}

TEST(Measurement, TopSurfaceKeysLoadAndABadValueIsNamed) {
  const auto o = load_semantic_options(
      YAML::Load("measurement: {bottom_face_band: 0.25, bottom_cut_reach: 0.05, top_surface_tolerance: 0.2, "
                 "bottom_face_min_length: 1.5}"),
      "s.yaml");
  EXPECT_DOUBLE_EQ(o.measurement.bottom_face_band, 0.25);
  EXPECT_DOUBLE_EQ(o.measurement.bottom_cut_reach, 0.05);
  EXPECT_DOUBLE_EQ(o.measurement.top_surface_tolerance, 0.2);
  EXPECT_DOUBLE_EQ(o.measurement.bottom_face_min_length, 1.5);
  test::expect_load_error_names("measurement: {bottom_face_band: 2}", "semantics.measurement.bottom_face_band");
}

// A cabinet behind a bed: the bed hides the cabinet's lower half, so its visible part ends at the
// bed, not at its own bottom. It is completed from the class height (0.8 m) down from its real top.
TEST(Measurement, BottomOccludedBoxIsCompletedFromTheClassHeight) {
  SemanticOptions o;
  const Eigen::Vector3d up(0, -1, 0);
  // Cabinet face at z = 4 m over x in [-0.25, 0.25], y (down) in [-0.4, 0.4]: u in [288, 351],
  // v in [189.5, 289.5]. Bed face at z = 3 m from v = 240 down, wide: the cabinet shows v < 240.
  cv::Mat d = scene(8.0, 4.0, 288, 351, 190, 290);
  d(cv::Rect(200, 240, 240, 160)).setTo(3.0);
  const Eigen::Vector4d cabinet(288, 190, 351, 239), bed(200, 240, 440, 400);
  const auto p = measure_pose_from_depth(d, camera(), slam::SE3(), cabinet, up, "cabinet", o, {{bed, std::nullopt}});
  ASSERT_TRUE(p);
  // True centre height: y = 0 (the visible half alone would put it at y = -0.2).
  EXPECT_NEAR(p->pose.translation().y(), 0.0, 0.04);
  EXPECT_NEAR(p->size.z(), 0.8, 0.04);
  // Without the occluder below it, the box is taken as the whole cabinet: its centre is the visible half's.
  const auto alone = measure_pose_from_depth(d, camera(), slam::SE3(), cabinet, up, "cabinet", o);
  ASSERT_TRUE(alone);
  EXPECT_LT(alone->pose.translation().y(), -0.15);
}

// A chair gives points mostly on its seat and backrest, few on its legs: its height comes from the
// box's rows at the points' depth, not from the 5-95 % extent of the points.
TEST(Measurement, ThinClassHeightFromTheBoxRows) {
  SemanticOptions o;
  const Eigen::Vector3d up(0, -1, 0);
  // Chair 0.85 m tall standing on a floor at y = 1.2 (camera 1.2 m up), front at z = 3: rows
  // v = 239.5 + 500 y / 3 give the top (y = 0.35) at 297.8 and the feet at 439.5. Only the seat and
  // back (y in [0.35, 0.8]) are drawn solid; the legs are two thin columns.
  cv::Mat d(480, 640, CV_32F, cv::Scalar(9.0f));
  d(cv::Rect(280, 298, 80, 76)).setTo(3.0);   // back and seat
  d(cv::Rect(284, 374, 3, 66)).setTo(3.0);    // legs
  d(cv::Rect(353, 374, 3, 66)).setTo(3.0);
  const Eigen::Vector4d box(280, 298, 360, 439);
  const auto p = measure_pose_from_depth(d, camera(), slam::SE3(), box, up, "chair", o);
  ASSERT_TRUE(p);
  EXPECT_NEAR(p->pose.translation().y(), 1.2 - 0.425, 0.04);
  o.measurement.thin_height_from_box_rows = false;
  const auto points_only = measure_pose_from_depth(d, camera(), slam::SE3(), box, up, "chair", o);
  ASSERT_TRUE(points_only);
  EXPECT_LT(points_only->pose.translation().y(), 1.2 - 0.425 - 0.06);  // the legs' few points barely count
}

// Depth (camera z) of a floor (world z = 0, up = +z) and of boxes (an object's parts: a bed's, a
// chair's), each given by its centre and half size in the object's frame: the object stands at
// `centre` (on the floor), turned by yaw about up (a bed's length along its own y). Seen by a camera
// at `eye` looking along world x, pitched down. Returns the depth, the object's image box and the
// camera pose.
struct BoxView {
  cv::Mat depth;
  Eigen::Vector4d box;
  slam::SE3 T_wc;
};
struct Part {
  Eigen::Vector3d centre, half;
  bool of_object = true;  // false: in the scene, not in the object's image box
};
BoxView object_on_floor(const std::vector<Part>& parts, const Eigen::Vector3d& centre, double yaw_deg,
                     const Eigen::Vector3d& eye, double pitch_deg) {
  const auto cam = camera();
  Eigen::Matrix3d level;  // camera z = world x, camera x = -world y, camera y = -world z
  level << 0, 0, 1, -1, 0, 0, 0, -1, 0;
  const Eigen::Matrix3d R_wc = level * Eigen::AngleAxisd(-pitch_deg * M_PI / 180, Eigen::Vector3d::UnitX()).toRotationMatrix();
  const Eigen::Matrix3d R_wb = Eigen::AngleAxisd(yaw_deg * M_PI / 180, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  BoxView v{cv::Mat(480, 640, CV_32F, cv::Scalar(0.0f)), Eigen::Vector4d(640, 480, -1, -1), slam::SE3(R_wc, eye)};
  for (int y = 0; y < 480; ++y)
    for (int x = 0; x < 640; ++x) {
      const Eigen::Vector3d ray_c = cam.unproject(Eigen::Vector2d(x, y)), ray = R_wc * ray_c;
      double t = ray.z() < 0 ? -eye.z() / ray.z() : 1e9;  // the floor
      bool on_object = false;
      for (const Part& part : parts) {
        // Slabs of the part, in the bed's frame.
        const Eigen::Vector3d o = R_wb.transpose() * (eye - centre) - part.centre, r = R_wb.transpose() * ray;
        double t0 = 0, t1 = 1e9;
        for (int k = 0; k < 3; ++k) {
          if (std::abs(r(k)) < 1e-12) {
            if (std::abs(o(k)) > part.half(k)) t0 = 2e9;
            continue;
          }
          const double a = (-part.half(k) - o(k)) / r(k), b = (part.half(k) - o(k)) / r(k);
          t0 = std::max(t0, std::min(a, b)), t1 = std::min(t1, std::max(a, b));
        }
        if (t0 <= t1 && t0 < t) t = t0, on_object = part.of_object;
      }
      if (t < 1e8 && ray_c.z() * t < 10) v.depth.at<float>(y, x) = static_cast<float>(ray_c.z() * t);
      if (on_object)
        v.box = Eigen::Vector4d(std::min<double>(v.box(0), x), std::min<double>(v.box(1), y),
                                std::max<double>(v.box(2), x), std::max<double>(v.box(3), y));
    }
  return v;
}

// A bed seen from above and beside its foot shows its foot, its top and one side; their points
// crowd at the near corner, and their principal axes run off the bed's length. The normals of its
// vertical faces give its axes, and its side face its centre across.
TEST(Measurement, LongClassAxesAndSideFromItsVerticalFaces) {
  SemanticOptions o;
  const double yaw = -70;  // the bed's length 20 degrees off the line of sight, its foot towards the camera
  const Eigen::Vector3d centre(4.5, 0.4, 0.3);
  const BoxView v = object_on_floor({{Eigen::Vector3d::Zero(), Eigen::Vector3d(0.5, 1.0, 0.3)}}, centre, yaw,
                                 Eigen::Vector3d(0, 0, 1.6), 22);
  ASSERT_GT(v.box(0), 2);  // whole in the image
  ASSERT_LT(v.box(3), 477);
  const Eigen::Vector3d length(-std::sin(yaw * M_PI / 180), std::cos(yaw * M_PI / 180), 0);
  const Eigen::Vector3d across = Eigen::Vector3d::UnitZ().cross(length);
  const auto measure = [&](const SemanticOptions& opts) {
    return measure_pose_from_depth(v.depth, camera(), v.T_wc, v.box, Eigen::Vector3d::UnitZ(), "bed", opts);
  };
  const auto axis_error_deg = [&](const ObjectPose& p) {  // of the box axis nearer the bed's length
    const Eigen::Matrix3d R = p.pose.rotation_matrix();
    return std::acos(std::min(1.0, std::max(std::abs(R.col(0).dot(length)), std::abs(R.col(1).dot(length))))) * 180 / M_PI;
  };
  const auto p = measure(o);
  ASSERT_TRUE(p);
  EXPECT_LT(axis_error_deg(*p), 1.0);
  // Along: the foot pushed back by half the class's 2 m. Across: the side pushed back by half the
  // class's 0.95 m, 0.025 m off this 1 m wide bed.
  EXPECT_NEAR((p->pose.translation() - centre).dot(length), 0.0, 0.02);
  EXPECT_NEAR((p->pose.translation() - centre).dot(across), 0.025, 0.02);
  // Without the side: the middle of the points across, towards the camera.
  o.measurement.anchor_side_face = false;
  const auto middle = measure(o);
  ASSERT_TRUE(middle);
  EXPECT_GT((middle->pose.translation() - centre).dot(across), 0.1);
  // The principal axes run 30 degrees off, and the centre half a metre.
  o.measurement.axes_from_planes = false;
  const auto pca = measure(o);
  ASSERT_TRUE(pca);
  EXPECT_GT(axis_error_deg(*pca), 20.0);
  EXPECT_GT((pca->pose.translation() - centre).head<2>().norm(), 0.4);
  EXPECT_TRUE(SemanticOptions().plane_axes_classes.count("bed"));
  expect_switch_on_by_default("axes_from_planes", [](const SemanticOptions& s) { return s.measurement.axes_from_planes; });
  expect_switch_on_by_default("anchor_side_face", [](const SemanticOptions& s) { return s.measurement.anchor_side_face; });
}

// Seen along its length from near its foot, a bed standing 0.5 m from a wall shows the wall beyond
// its far side: a face across its width that looks towards the camera from behind the bed. It does
// not place the bed's side (taken for it, the bed would be pushed 1.5 m, onto the wall's far side).
TEST(Measurement, AFaceBehindTheBedDoesNotPlaceItsSide) {
  SemanticOptions o;
  const Eigen::Vector3d centre(4.0, 0.0, 0.0);  // the bed's length along world x (yaw -90 degrees)
  const std::vector<Part> scene = {{Eigen::Vector3d(0, 0, 0.3), Eigen::Vector3d(0.5, 1.0, 0.3)},
                                   {Eigen::Vector3d(-1.0, 0, 0.75), Eigen::Vector3d(0.01, 2.5, 0.75), false}};  // wall, y = 1
  const Eigen::Vector3d eye(1.5, -0.6, 1.9);
  const BoxView v = object_on_floor(scene, centre, -90, eye, std::atan2(eye.z() - 0.3, centre.x() - eye.x()) * 180 / M_PI);
  ASSERT_GT(v.box(0), 2);  // whole in the image
  ASSERT_LT(v.box(2), 637);
  ASSERT_LT(v.box(3), 477);
  const auto p = measure_pose_from_depth(v.depth, camera(), v.T_wc, v.box, Eigen::Vector3d::UnitZ(), "bed", o);
  ASSERT_TRUE(p);
  EXPECT_NEAR(p->pose.translation().x(), centre.x(), 0.05);
  EXPECT_LT(std::abs(p->pose.translation().y() - centre.y()), 0.15);
}

// A chair's parts as boxes (seat, back, four legs), its front towards +y.
std::vector<Part> chair_parts() {
  return {{Eigen::Vector3d(0, 0.01, 0.45), Eigen::Vector3d(0.25, 0.24, 0.03)},       // seat
          {Eigen::Vector3d(0, -0.225, 0.665), Eigen::Vector3d(0.25, 0.025, 0.185)},  // back
          {Eigen::Vector3d(-0.225, -0.215, 0.21), Eigen::Vector3d(0.018, 0.018, 0.21)},
          {Eigen::Vector3d(0.225, -0.215, 0.21), Eigen::Vector3d(0.018, 0.018, 0.21)},
          {Eigen::Vector3d(-0.225, 0.215, 0.21), Eigen::Vector3d(0.018, 0.018, 0.21)},
          {Eigen::Vector3d(0.225, 0.215, 0.21), Eigen::Vector3d(0.018, 0.018, 0.21)}};
}

// A chair (the synthetic one: seat, backrest, four legs) seen 35 degrees off its front shows its
// seat's front and side edges and its backrest in an L, whose principal axes run 24 degrees off: the
// front, anchored on the nearest corner, put the centre 0.06 m off. The normals of the backrest and
// the edges give its axes (0.03 degrees off), and its front and side faces its centre (exact here).
TEST(Measurement, ChairAxesAndCentreFromItsVerticalFaces) {
  SemanticOptions o;
  const std::vector<Part> chair = chair_parts();
  const Eigen::Vector3d centre(3.5, 0.3, 0.0), eye(0, 0, 1.4);
  const double yaw = 55;  // its front (+y) turned 35 degrees from the camera
  const BoxView v = object_on_floor(chair, centre, yaw, eye, std::atan2(eye.z() - 0.45, centre.x()) * 180 / M_PI);
  ASSERT_GT(v.box(0), 2);  // whole in the image
  ASSERT_LT(v.box(2), 637);
  ASSERT_LT(v.box(3), 477);
  const Eigen::Vector3d front(-std::sin(yaw * M_PI / 180), std::cos(yaw * M_PI / 180), 0);
  const auto measure = [&](const SemanticOptions& opts) {
    return measure_pose_from_depth(v.depth, camera(), v.T_wc, v.box, Eigen::Vector3d::UnitZ(), "chair", opts);
  };
  const auto axis_error_deg = [&](const ObjectPose& p) {
    const Eigen::Matrix3d R = p.pose.rotation_matrix();
    return std::acos(std::min(1.0, std::max(std::abs(R.col(0).dot(front)), std::abs(R.col(1).dot(front))))) * 180 / M_PI;
  };
  const auto p = measure(o);
  ASSERT_TRUE(p);
  EXPECT_LT(axis_error_deg(*p), 2.0);
  EXPECT_LT((p->pose.translation() - centre).head<2>().norm(), 0.05);
  o.measurement.axes_from_planes = false;
  const auto pca = measure(o);
  ASSERT_TRUE(pca);
  EXPECT_GT(axis_error_deg(*pca), 15.0);
  EXPECT_GT((pca->pose.translation() - centre).head<2>().norm(), 0.04);  // 0.062 m, 0.047 m of it towards its front
  EXPECT_TRUE(SemanticOptions().plane_axes_classes.count("chair"));
}

// A chair cut by the left border gets no pose: its nearest points show no face to complete along.
// Measured as if uncut (for a landmark nothing else places), its centre comes from its seen part:
// off by a part of its width across the view.
TEST(Measurement, ThinSideCutMeasuredAsIfUncut) {
  const SemanticOptions o;
  const Eigen::Vector3d centre(3.0, 1.85, 0.0), eye(0, 0, 1.4);
  const BoxView v =
      object_on_floor(chair_parts(), centre, 30, eye, std::atan2(eye.z() - 0.45, centre.x()) * 180 / M_PI);
  ASSERT_LE(v.box(0), 0);    // cut by the left border
  ASSERT_GT(v.box(2), 40);   // a good part of it in view
  ASSERT_LT(v.box(3), 477);  // not at the bottom
  const Eigen::Vector3d up = Eigen::Vector3d::UnitZ();
  EXPECT_FALSE(measure_pose_from_depth(v.depth, camera(), v.T_wc, v.box, up, "chair", o));
  const auto p = measure_thin_side_cut(v.depth, camera(), v.T_wc, v.box, up, "chair", o);
  ASSERT_TRUE(p);
  EXPECT_LT((p->pose.translation() - centre).head<2>().norm(), 0.15);  // 0.09 m here; 0.15 m with 0.15 m more cut
  // Only thin classes, only side cuts: a cabinet's side cut is completed along its face instead,
  // and an uncut chair has its pose already.
  EXPECT_FALSE(measure_thin_side_cut(v.depth, camera(), v.T_wc, v.box, up, "cabinet", o));
  // A keyframe's measurement gives it for the box alone, and none when a nearer detection overlaps
  // the box: what the side cut and the occluder leave of it may be its far part.
  std::vector<std::optional<ObjectPose>> side_cut;
  EXPECT_FALSE(measure_keyframe_poses(v.depth, camera(), v.T_wc, {v.box}, {"chair"}, up, o, &side_cut)[0]);
  ASSERT_EQ(side_cut.size(), 1u);
  EXPECT_TRUE(side_cut[0]);
  // Something 1.5 m away covers the chair's box from its middle column to 30 px beyond it.
  cv::Mat occluded = v.depth.clone();
  const int x_mid = static_cast<int>(0.5 * (v.box(0) + v.box(2))),
            y_mid = static_cast<int>(0.5 * (v.box(1) + v.box(3)));
  const Eigen::Vector4d in_front(x_mid, y_mid, v.box(2) + 30, 479);
  occluded(cv::Rect(x_mid, y_mid, static_cast<int>(in_front(2)) - x_mid + 1, 480 - y_mid)).setTo(1.5f);
  measure_keyframe_poses(occluded, camera(), v.T_wc, {v.box, in_front}, {"chair", "cabinet"}, up, o, &side_cut);
  ASSERT_EQ(side_cut.size(), 2u);
  EXPECT_FALSE(side_cut[0]);
  const Eigen::Vector3d inside(3.0, 0.3, 0.0);
  const BoxView whole =
      object_on_floor(chair_parts(), inside, 30, eye, std::atan2(eye.z() - 0.45, inside.x()) * 180 / M_PI);
  ASSERT_GT(whole.box(0), 2);
  EXPECT_TRUE(measure_pose_from_depth(whole.depth, camera(), whole.T_wc, whole.box, up, "chair", o));
  EXPECT_FALSE(measure_thin_side_cut(whole.depth, camera(), whole.T_wc, whole.box, up, "chair", o));
}

// The synthetic wheelchair's parts as boxes, its front towards +y: they span y -0.42..0.51.
std::vector<Part> wheelchair_parts() {
  std::vector<Part> chair = {{Eigen::Vector3d(0, 0.02, 0.50), Eigen::Vector3d(0.22, 0.22, 0.03)},   // seat
                             {Eigen::Vector3d(0, -0.23, 0.72), Eigen::Vector3d(0.22, 0.015, 0.19)},  // backrest
                             {Eigen::Vector3d(0, 0.45, 0.12), Eigen::Vector3d(0.17, 0.06, 0.01)}};   // footplate
  for (const double sx : {-1.0, 1.0}) {
    chair.push_back({Eigen::Vector3d(sx * 0.30, -0.12, 0.30), Eigen::Vector3d(0.02, 0.30, 0.30)});   // wheel
    chair.push_back({Eigen::Vector3d(sx * 0.24, 0.38, 0.08), Eigen::Vector3d(0.015, 0.02, 0.08)});   // caster
    chair.push_back({Eigen::Vector3d(sx * 0.16, 0.36, 0.30), Eigen::Vector3d(0.012, 0.012, 0.2)});   // strut
    chair.push_back({Eigen::Vector3d(sx * 0.25, 0.0, 0.68), Eigen::Vector3d(0.02, 0.18, 0.015)});    // armrest
  }
  return chair;
}

// A wheelchair seen from its front (the synthetic one's parts as boxes): its box's bottom row shows
// where its casters meet the floor, 0.11 m behind its footplate, and the footplate stands in the
// bottom rows that box_shrink trims. The parts just above the floor in those rows give its front.
TEST(Measurement, WheelchairFrontFromItsFootplate) {
  SemanticOptions o;
  const std::vector<Part> chair = wheelchair_parts();
  const Eigen::Vector3d origin(5.0, 0.0, 0.0), eye(0, 0, 1.2);
  const BoxView v = object_on_floor(chair, origin, 90, eye, std::atan2(eye.z() - 0.45, origin.x()) * 180 / M_PI);
  ASSERT_LT(v.box(3), 470);  // the floor shows below the box
  // Its front (+y) faces the camera (-x); its parts span y -0.42..0.51, so its centre lies 0.045 m
  // towards the camera from the origin.
  const double truth = origin.x() - 0.045;
  const auto centre_x = [&]() {
    const auto p = measure_pose_from_depth(v.depth, camera(), v.T_wc, v.box, Eigen::Vector3d::UnitZ(), "wheelchair", o);
    return p ? p->pose.translation().x() : -1.0;
  };
  // The class is 1.0 m long, the model 0.93 m: the centre half a class length behind the footplate.
  EXPECT_NEAR(centre_x(), truth + 0.035, 0.02);
  o.measurement.front_from_low_rows = false;  // from the casters' foot
  EXPECT_GT(centre_x(), truth + 0.1);
  expect_switch_on_by_default("front_from_low_rows", [](const SemanticOptions& s) { return s.measurement.front_from_low_rows; });
  EXPECT_DOUBLE_EQ(
      load_semantic_options(YAML::Load("measurement: {floor_clearance: 0.05}"), "s.yaml").measurement.floor_clearance, 0.05);
  test::expect_load_error_names("measurement: {floor_clearance: -1}", "semantics.measurement.floor_clearance");
}

// A wheelchair seen from its front at 1.6 m, its box cut by the image's bottom: its footplate and
// casters are out of view, its nearest parts (the seat's and armrests' fronts) 0.3-0.4 m behind its
// front. The middle of its parts in the upper half of its height (seat and armrests to backrest)
// gives its centre (measurement.centre_from_upper_part_when_cut).
TEST(Measurement, BottomCutWheelchairCentreFromItsUpperPart) {
  SemanticOptions o;
  const Eigen::Vector3d origin(1.6, 0.0, 0.0), eye(0, 0, 1.2);
  const BoxView v = object_on_floor(wheelchair_parts(), origin, 90, eye, 8);
  ASSERT_GE(v.box(3), 478);  // cut by the bottom border
  ASSERT_GT(v.box(1), 2);    // not at the top
  const double truth = origin.x() - 0.045;
  const auto centre_x = [&]() {
    const auto p = measure_pose_from_depth(v.depth, camera(), v.T_wc, v.box, Eigen::Vector3d::UnitZ(), "wheelchair", o);
    return p ? p->pose.translation().x() : -1.0;
  };
  const double from_upper = centre_x();
  EXPECT_NEAR(from_upper, truth, 0.08);
  o.measurement.centre_from_upper_part_when_cut = false;  // from its nearest points
  EXPECT_GT(centre_x(), truth + 0.2);
  expect_switch_on_by_default("centre_from_upper_part_when_cut",
                              [](const SemanticOptions& s) { return s.measurement.centre_from_upper_part_when_cut; });
}

TEST(Measurement, UpFromCameraPoses) {
  // Upright cameras looking along world x in a z-up world: camera y (down) = world -z.
  Eigen::Matrix3d R;
  R << 0, 0, 1, -1, 0, 0, 0, -1, 0;
  const slam::SE3 T(R, Eigen::Vector3d(1, 2, 1.2));
  EXPECT_LT((estimate_up({T, T}) - Eigen::Vector3d::UnitZ()).norm(), 1e-12);
}

// Cameras looking 18 degrees down (the synthetic ward's robot) while turning: their -y axes lean
// towards their views, their right axes stay horizontal, and up is found orthogonal to those.
TEST(Measurement, UpFromCamerasThatLookDown) {
  const auto camera_at = [](double yaw_deg, double pitch_deg) {
    const double yaw = yaw_deg * M_PI / 180, pitch = pitch_deg * M_PI / 180;
    // Level camera looking along world x (camera z = x, x = -y, y = -z), turned by yaw about z,
    // then pitched down about its own x axis.
    Eigen::Matrix3d level;
    level << 0, 0, 1, -1, 0, 0, 0, -1, 0;
    const Eigen::Matrix3d R = Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix() * level *
                              Eigen::AngleAxisd(-pitch, Eigen::Vector3d::UnitX()).toRotationMatrix();
    return slam::SE3(R, Eigen::Vector3d::Zero());
  };
  std::vector<slam::SE3> turning;
  for (int yaw = 0; yaw <= 90; yaw += 10) turning.push_back(camera_at(yaw, 18));
  ASSERT_GT(-turning.front().rotation_matrix().col(2).z(), 0.3);  // it does look down
  const Eigen::Vector3d up = estimate_up(turning);
  EXPECT_LT(std::acos(std::min(1.0, up.z())) * 180 / M_PI, 0.01);
  // Never turning, the pitch cannot be told from the right axes: up stays orthogonal to them.
  const std::vector<slam::SE3> straight(3, camera_at(30, 18));
  const Eigen::Vector3d still = estimate_up(straight);
  EXPECT_LT(std::abs(still.dot(straight.front().rotation_matrix().col(0))), 1e-9);
  EXPECT_NEAR(std::acos(still.z()) * 180 / M_PI, 18, 0.01);
}

}  // namespace
}  // namespace wardmap::semantics
