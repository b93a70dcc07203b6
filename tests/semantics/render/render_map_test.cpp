// map.glb read back for drawing (no display needed), and 'wardmap render-map' end to end under
// xvfb-run: the PNG's size, that it is not one flat colour, that the boxes show in their class
// colours; bad input exits 2 naming the file; no display gives the xvfb-run advice.
#include "semantics/render/map_render.h"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>

#include "semantics/export/gltf_export.h"
#include "slam/core/errors.h"
#include "tests/semantics/gltf_test_objects.h"
#include "tests/apps/cli_support.h"

namespace wardmap::test {
namespace {

namespace fs = std::filesystem;
using semantics::GltfMapContent;
using semantics::GltfObject;


// A z-up room: two doors, a bed (large top faces for the top view), a chair; a trajectory; points.
GltfMapContent sample_map() {
  GltfMapContent c;
  c.objects = {upright_box(1, "door", {0.0, 3.0, 1.0}, 0.0, {1.6, 1.2, 2.0}), upright_box(2, "door", {4.0, 3.0, 1.0}, 0.4, {1.6, 1.2, 2.0}),
               upright_box(3, "bed", {2.0, -1.0, 0.3}, 0.0, {1.0, 2.0, 0.6}), upright_box(4, "chair", {-1.5, 0.0, 0.45}, 0.0, {0.5, 0.5, 0.9})};
  for (int i = 0; i <= 40; ++i) c.trajectory.emplace_back(-1.0 + 0.12 * i, 1.0 + 0.3 * std::sin(0.2 * i), 1.4);
  for (int i = 0; i < 300; ++i) c.points.emplace_back(-2.0 + 0.02 * i, 4.0, 0.5 + 0.005 * i);
  return c;
}

fs::path write_sample(const fs::path& dir) {
  const fs::path glb = dir / "map.glb";
  semantics::write_map_glb(glb, sample_map());
  return glb;
}

bool have_xvfb() { return run_command("command -v xvfb-run >/dev/null") == 0; }

// 'wardmap render-map ARGS' under a fresh virtual display.
// Up to three attempts when the X server, not wardmap, failed: `xvfb-run -a` picks a display that
// another Xvfb on the shared machine can take between its check and its server's start ("bad X
// server connection", seen under load even with the tests serialised).
CliResult render_under_xvfb(const std::string& args) {
  CliResult r;
  for (int attempt = 0; attempt < 3; ++attempt) {
    r.output.clear();
    r.code = run_command(
        "xvfb-run -a -s '-screen 0 1280x1024x24' " + shq(binary_dir() / "apps" / "wardmap") + " render-map " + args,
        &r.output);
    if (r.code == 0 || r.output.find("bad X server connection") == std::string::npos) break;
  }
  return r;
}

// Pixels within `tol` (per channel, 0-255) of an RGBA 0-1 colour.
int pixels_near(const cv::Mat& bgr, const Eigen::Vector4f& rgba, int tol) {
  const cv::Vec3b want(cv::saturate_cast<uchar>(255 * rgba[2]), cv::saturate_cast<uchar>(255 * rgba[1]),
                       cv::saturate_cast<uchar>(255 * rgba[0]));
  int n = 0;
  for (int y = 0; y < bgr.rows; ++y)
    for (int x = 0; x < bgr.cols; ++x) {
      const cv::Vec3b p = bgr.at<cv::Vec3b>(y, x);
      if (std::abs(p[0] - want[0]) <= tol && std::abs(p[1] - want[1]) <= tol && std::abs(p[2] - want[2]) <= tol) ++n;
    }
  return n;
}

TEST(RenderMapScene, ReadsWhatTheExporterWrites) {
  const fs::path glb = write_sample(scratch_dir());
  const semantics::MapScene s = semantics::read_map_scene(glb);
  ASSERT_EQ(s.objects.size(), 4u);
  EXPECT_EQ(s.objects[0].label, "door");
  EXPECT_EQ(s.objects[0].id, 1);
  EXPECT_EQ(s.objects[2].label, "bed");
  EXPECT_EQ(s.objects[0].triangles.size(), 36u);  // the unit cube: 12 triangles
  EXPECT_TRUE(s.objects[0].colour.isApprox(semantics::class_colour("door")));
  ASSERT_EQ(s.lines.size(), 1u);
  EXPECT_EQ(s.lines[0].points.size(), 41u);
  ASSERT_EQ(s.points.size(), 1u);
  EXPECT_EQ(s.points[0].points.size(), 300u);
  // The root node turns the map's z-up onto glTF's +Y: the trajectory's 1.4 m height is y = 1.4.
  for (const auto& p : s.lines[0].points) EXPECT_NEAR(p.y(), 1.4, 1e-5);
  // The door's box: centre (0, 3, 1) in the map, so (0, 1, -3) in glTF; 2 m high along +Y.
  Eigen::AlignedBox3d b;
  for (const auto& v : s.objects[0].vertices) b.extend((s.objects[0].world * v.cast<double>().homogeneous()).head<3>());
  EXPECT_TRUE(b.center().isApprox(Eigen::Vector3d(0, 1, -3), 1e-5)) << b.center().transpose();
  EXPECT_NEAR(b.sizes().y(), 2.0, 1e-5);
}

TEST(RenderMapScene, RejectsMissingAndNonGlbFiles) {
  const fs::path dir = scratch_dir();
  try {
    semantics::read_map_scene(dir / "absent.glb");
    FAIL() << "no error for a missing file";
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), (dir / "absent.glb").string());
  }
  std::ofstream(dir / "text.glb") << "this is not a glTF file\n";
  try {
    semantics::read_map_scene(dir / "text.glb");
    FAIL() << "no error for a text file";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("not a binary glTF"), std::string::npos) << e.what();
  }
}

TEST(RenderMapText, CountsTakeTheirNounsNumber) {
  EXPECT_EQ(semantics::counted(0, "object"), "0 objects");
  EXPECT_EQ(semantics::counted(1, "object"), "1 object");
  EXPECT_EQ(semantics::counted(9, "map point"), "9 map points");
}

TEST(RenderMapCli, TopViewShowsTheClassColours) {
  if (!have_xvfb()) GTEST_SKIP() << "xvfb-run not found (Debian package xvfb): cannot draw without an X display";
  const fs::path dir = scratch_dir();
  write_sample(dir);
  const fs::path png = dir / "top.png";
  // The run folder form: its map.glb.
  const CliResult r = render_under_xvfb(shq(dir) + " --out " + shq(png) + " --width 640 --height 480 --view top");
  ASSERT_EQ(r.code, 0) << r.output;
  const cv::Mat img = cv::imread(png.string(), cv::IMREAD_COLOR);
  ASSERT_FALSE(img.empty()) << "no PNG at " << png;
  EXPECT_EQ(img.cols, 640);
  EXPECT_EQ(img.rows, 480);
  cv::Scalar mean, stddev;
  cv::meanStdDev(img, mean, stddev);
  EXPECT_GT(stddev[0] + stddev[1] + stddev[2], 10.0) << "a flat picture";
  // The top faces, turned to the camera, show the exact class colour; far more pixels than the
  // legend's swatches alone.
  EXPECT_GT(pixels_near(img, semantics::class_colour("door"), 12), 2000);
  EXPECT_GT(pixels_near(img, semantics::class_colour("bed"), 12), 1000);
  EXPECT_GT(pixels_near(img, semantics::class_colour("chair"), 12), 50);
}

TEST(RenderMapCli, ObliqueViewOfAGlbFile) {
  if (!have_xvfb()) GTEST_SKIP() << "xvfb-run not found (Debian package xvfb): cannot draw without an X display";
  const fs::path dir = scratch_dir();
  const fs::path glb = write_sample(dir);
  const fs::path png = dir / "sub" / "oblique.png";
  const CliResult r = render_under_xvfb(shq(glb) + " --out " + shq(png) + " --width 800 --height 600 --view oblique");
  ASSERT_EQ(r.code, 0) << r.output;
  const cv::Mat img = cv::imread(png.string(), cv::IMREAD_COLOR);
  ASSERT_FALSE(img.empty());
  EXPECT_EQ(img.cols, 800);
  EXPECT_EQ(img.rows, 600);
  EXPECT_GT(pixels_near(img, semantics::class_colour("door"), 40), 500);
}

TEST(RenderMapCli, NonGlbFileExitsTwoNamingIt) {
  const fs::path dir = scratch_dir();
  const fs::path bad = dir / "notes.glb";
  std::ofstream(bad) << "plain text\n";
  // Bad input is reported before any display is needed: no xvfb-run here.
  const CliResult r = wardmap_cli("render-map " + shq(bad) + " --out " + shq(dir / "x.png"));
  EXPECT_EQ(r.code, 2) << r.output;
  EXPECT_NE(r.output.find("wardmap: error: " + bad.string() + ": not a binary glTF"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(dir / "x.png"));

  const CliResult missing = wardmap_cli("render-map " + shq(dir) + " --out " + shq(dir / "x.png"));
  EXPECT_EQ(missing.code, 2) << missing.output;
  EXPECT_NE(missing.output.find((dir / "map.glb").string()), std::string::npos) << missing.output;
}

TEST(RenderMapCli, NoDisplaySaysToUseXvfbRun) {
  const fs::path dir = scratch_dir();
  write_sample(dir);
  const CliResult r = [&] {
    CliResult c;
    c.code = run_command("env -u DISPLAY " + shq(binary_dir() / "apps" / "wardmap") + " render-map " + shq(dir) + " --out " +
                             shq(dir / "x.png"),
                         &c.output);
    return c;
  }();
  EXPECT_EQ(r.code, 1) << r.output;
  EXPECT_NE(r.output.find("DISPLAY is not set"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("xvfb-run"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(dir / "x.png"));
}

}  // namespace
}  // namespace wardmap::test
