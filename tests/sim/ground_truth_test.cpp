// Ground truth agrees with the pixels: annotated boxes of unoccluded objects match the projection
// of their true geometry, back-projected depth lies on the surface that was hit, and the
// annotations are what the instance buffer says.
#include <gtest/gtest.h>

#include "sim/sequence.h"
#include "sim/writer.h"
#include "tests/sim/sim_test_util.h"

namespace wardmap::sim {
namespace {

struct Extent {
  Eigen::Vector2d lo = Eigen::Vector2d::Constant(1e18), hi = Eigen::Vector2d::Constant(-1e18);
  bool in_front = true;
  void add(const slam::PinholeCamera& cam, const slam::SE3& T_cw, const Eigen::Vector3d& p_w) {
    const Eigen::Vector3d p = T_cw * p_w;
    if (p.z() < 0.1) in_front = false;
    const Eigen::Vector2d uv = cam.project(p);
    lo = lo.cwiseMin(uv);
    hi = hi.cwiseMax(uv);
  }
  bool inside(const slam::PinholeCamera& cam) const {
    return in_front && lo.x() > 1 && lo.y() > 1 && hi.x() < cam.width - 2 && hi.y() < cam.height - 2;
  }
};

// The annotated box (cv::Rect convention) as a continuous extent in pinhole pixel coordinates.
void expect_box_matches(const Annotation& a, const Extent& e, double tol, const std::string& what) {
  EXPECT_NEAR(a.box[0] - 0.5, e.lo.x(), tol) << what;
  EXPECT_NEAR(a.box[1] - 0.5, e.lo.y(), tol) << what;
  EXPECT_NEAR(a.box[2] - 0.5, e.hi.x(), tol) << what;
  EXPECT_NEAR(a.box[3] - 0.5, e.hi.y(), tol) << what;
}

void check_sequence(const std::string& name, Variant variant, int frames, int step) {
  SCOPED_TRACE(name);
  SequenceOptions o;
  o.variant = variant;
  o.seed = 5;
  o.width = 320;
  o.height = 240;
  RenderOptions ro;
  ro.triangle_ids = true;
  Sequence seq(testing::builtin(name), o, ro);
  const Scene& scene = seq.scene();
  const slam::PinholeCamera& cam = seq.camera();
  int boxes_checked = 0, obb_checked = 0;
  long depth_checked = 0;
  Frame f;
  for (int i = 0; i < std::min(frames, seq.frame_count()); i += step) {
    seq.render(i, f, true);
    const slam::SE3 T_cw = f.T_wc.inverse();
    // depth as written (uint16, factor 5000) back-projected onto the plane of the triangle hit
    const cv::Mat d16 = depth_to_png16(f.buffers.depth);
    double worst = 0;
    for (int v = 0; v < cam.height; ++v)
      for (int u = 0; u < cam.width; ++u) {
        const int tri = f.buffers.triangle.at<int>(v, u);
        ASSERT_GE(tri, 0) << "hole in the scene at " << u << "," << v << " frame " << i;
        const Triangle& t = scene.triangles[static_cast<size_t>(tri)];
        ASSERT_EQ(f.buffers.instance.at<int>(v, u), t.instance);
        const uint16_t raw = d16.at<uint16_t>(v, u);
        if (raw == 0) continue;  // beyond 13.1 m
        const double z = raw / kDepthFactor;
        const Eigen::Vector3d p_c((u - cam.cx) * z / cam.fx, (v - cam.cy) * z / cam.fy, z);
        const Eigen::Vector3d p_w = f.T_wc * p_c;
        const Eigen::Vector3d a = t.p[0].cast<double>();
        const Eigen::Vector3d n = (t.p[1].cast<double>() - a).cross(t.p[2].cast<double>() - a).normalized();
        worst = std::max(worst, std::abs(n.dot(p_w - a)));
        ++depth_checked;
      }
    EXPECT_LT(worst, 1e-3) << "frame " << i;
    // annotations = what the instance buffer holds
    std::map<int, std::array<int, 5>> from_buffer;  // id -> x0 y0 x1 y1 count
    for (int v = 0; v < cam.height; ++v)
      for (int u = 0; u < cam.width; ++u) {
        const int id = f.buffers.instance.at<int>(v, u);
        if (id == 0) continue;
        auto [it, fresh] = from_buffer.try_emplace(id, std::array<int, 5>{u, v, u + 1, v + 1, 0});
        auto& b = it->second;
        b = {std::min(b[0], u), std::min(b[1], v), std::max(b[2], u + 1), std::max(b[3], v + 1), b[4] + 1};
      }
    ASSERT_EQ(from_buffer.size(), f.annotations.size());
    for (const Annotation& a : f.annotations) {
      const auto& b = from_buffer.at(a.id);
      EXPECT_EQ(a.box[0], b[0]);
      EXPECT_EQ(a.box[1], b[1]);
      EXPECT_EQ(a.box[2], b[2]);
      EXPECT_EQ(a.box[3], b[3]);
      EXPECT_EQ(a.pixels, b[4]);
      EXPECT_GT(a.visible, 0.0);
      EXPECT_LE(a.visible, 1.0);
      EXPECT_EQ(a.cls, scene.object(a.id).cls);
      // unoccluded and wholly inside: the box is the projection of the true geometry
      const ObjectInstance& obj = scene.object(a.id);
      Extent mesh, obb;
      for (int k = obj.first_triangle; k < obj.first_triangle + obj.triangle_count; ++k)
        for (const auto& p : scene.triangles[static_cast<size_t>(k)].p) mesh.add(cam, T_cw, p.cast<double>());
      for (const Eigen::Vector3d& c : scene.box_corners(a.id)) obb.add(cam, T_cw, c);
      // (thin parts -- an IV pole's 4 cm pole -- fall between pixel centres when far: near objects only)
      if (a.visible < 0.99 || !mesh.inside(cam) || mesh.hi.y() - mesh.lo.y() < 60) continue;
      const std::string what = "object " + std::to_string(a.id) + " frame " + std::to_string(i);
      expect_box_matches(a, mesh, 1.0, what);
      ++boxes_checked;
      // the oriented box itself, for the classes whose geometry fills their box's corners
      if (obj.cls == ObjectClass::kCabinet || obj.cls == ObjectClass::kDoor) {
        expect_box_matches(a, obb, 1.0, what + " (box corners)");
        ++obb_checked;
      }
      // and the object's triangles all lie inside its box
      for (int k = obj.first_triangle; k < obj.first_triangle + obj.triangle_count; ++k)
        for (const auto& p : scene.triangles[static_cast<size_t>(k)].p) {
          const Eigen::Vector3d l = obj.pose.inverse() * p.cast<double>();
          EXPECT_TRUE((l.cwiseAbs() - 0.5 * obj.size).maxCoeff() < 1e-4) << what;
        }
    }
  }
  EXPECT_GT(boxes_checked, 10);
  EXPECT_GT(depth_checked, 100000);
  std::printf("[ %s ] %d unoccluded boxes checked (%d against box corners), %ld depth pixels\n", name.c_str(),
              boxes_checked, obb_checked, depth_checked);
}

TEST(GroundTruth, AisleStraight) { check_sequence("aisle_straight", Variant::kQuick, 200, 4); }
TEST(GroundTruth, Ward) { check_sequence("ward", Variant::kQuick, 240, 4); }
TEST(GroundTruth, CorridorLoss) { check_sequence("corridor_loss", Variant::kQuick, 60, 2); }

}  // namespace
}  // namespace wardmap::sim
