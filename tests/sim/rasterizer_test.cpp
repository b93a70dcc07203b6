// The rasteriser against analytic answers: floor depth per row, near-plane clipping, coverage.
#include "sim/rasterizer.h"

#include <gtest/gtest.h>

#include "sim/camera_path.h"
#include "sim/sequence.h"

namespace wardmap::sim {
namespace {

Scene floor_scene() {
  Scene s;
  s.textures.push_back(make_texture(cv::Mat(8, 8, CV_8UC3, cv::Scalar(100, 150, 200)), true));
  const Eigen::Vector3d q[4] = {{-50, 50, 0}, {50, 50, 0}, {50, -50, 0}, {-50, -50, 0}};
  add_quad(s.triangles, q, Eigen::Vector3d::UnitZ(), FaceMaterial{0, 10, 10}, 0, false);
  return s;
}

TEST(Rasterizer, FloorDepthMatchesAnalyticPlaneAcrossTheNearPlane) {
  const Scene scene = floor_scene();  // the floor runs far behind the camera: clipped at the near plane
  const slam::PinholeCamera cam = synth_camera(320, 240);
  Rasterizer r(scene, cam);
  RenderBuffers b;
  const double h = 1.2;
  r.render(slam::SE3(camera_rotation(0.3, 0, 0), Eigen::Vector3d(1, 2, h)), b);
  int checked = 0;
  for (int v = 0; v < cam.height; ++v)
    for (int u = 0; u < cam.width; ++u) {
      const float d = b.depth.at<float>(v, u);
      const double expected = v > cam.cy ? h * cam.fy / (v - cam.cy) : 1e9;
      if (expected < 40) {  // the floor ends 50 m away
        ASSERT_NEAR(d, expected, 1e-5 * expected) << u << "," << v;
        ++checked;
      } else if (v < cam.cy) {
        ASSERT_EQ(d, 0.0f);  // sky: nothing there
      }
    }
  EXPECT_GT(checked, 15000);
  // flat colour times shade / (1 + falloff z^2)
  const cv::Vec3b px = b.rgb.at<cv::Vec3b>(cam.height - 1, 0);
  const double z = h * cam.fy / (cam.height - 1 - cam.cy);
  EXPECT_NEAR(px[2], 200.0 / (1 + 0.006 * z * z), 1.0);
}

TEST(Rasterizer, NothingInsideTheNearPlane) {
  Scene s;
  s.textures.push_back(make_texture(cv::Mat(8, 8, CV_8UC3, cv::Scalar(255, 255, 255)), true));
  const Eigen::Vector3d q[4] = {{0.03, 1, 1}, {0.03, -1, 1}, {0.03, -1, -1}, {0.03, 1, -1}};
  add_quad(s.triangles, q, -Eigen::Vector3d::UnitX(), FaceMaterial{}, 0, true);
  Rasterizer r(s, synth_camera(64, 48));
  RenderBuffers b;
  r.render(slam::SE3(camera_rotation(0, 0, 0), Eigen::Vector3d::Zero()), b);
  EXPECT_EQ(cv::countNonZero(b.depth), 0);
}

TEST(Rasterizer, CoverageCountsPixelsOnce) {
  Scene s;
  s.textures.push_back(make_texture(cv::Mat(8, 8, CV_8UC3, cv::Scalar(255, 255, 255)), true));
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.translation() = Eigen::Vector3d(3, 0, 0);
  add_box(s.triangles, pose, Eigen::Vector3d(0.5, 0.5, 0.5), BoxMaterials::all(FaceMaterial{}), 1);
  ObjectInstance o;
  o.id = 1;
  o.triangle_count = static_cast<int>(s.triangles.size());
  s.objects.push_back(o);
  const slam::PinholeCamera cam = synth_camera(160, 120);
  Rasterizer r(s, cam);
  RenderBuffers b;
  const slam::SE3 T(camera_rotation(0, 0, 0), Eigen::Vector3d::Zero());
  r.render(T, b);
  const long visible = cv::countNonZero(b.instance);
  EXPECT_EQ(r.object_coverage(T, 1, 80, 60), visible);  // unoccluded and inside: all of it
  // the front face spans +-0.5 at 2.5 m: 2 * 0.5 / 2.5 * f pixels across
  EXPECT_NEAR(std::sqrt(static_cast<double>(visible)), cam.fx * 0.4, 1.5);
}

}  // namespace
}  // namespace wardmap::sim
