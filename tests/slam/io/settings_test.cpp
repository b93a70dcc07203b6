#include "slam/io/settings.h"

#include <gtest/gtest.h>

#include <fstream>

#include "slam/core/errors.h"
#include "slam/io/sequence.h"
#include "tests/support/test_support.h"

namespace wardmap::slam::io {

namespace {

// A distortion-free camera with fx = fy = f.
PinholeCamera pinhole(int width, int height, double f, double cx, double cy) {
  PinholeCamera c;
  c.width = width;
  c.height = height;
  c.fx = c.fy = f;
  c.cx = cx;
  c.cy = cy;
  return c;
}

}  // namespace
namespace {

std::string error_of(const std::string& yaml) {
  try {
    parse_settings(yaml, "s.yaml");
  } catch (const InputError& e) {
    return e.what();
  }
  return "(no error)";
}

const char* kOrbSlam3 = R"(%YAML:1.0
Camera.type: "PinHole"
Camera1.fx: 517.306408
Camera1.fy: 516.469215
Camera1.cx: 318.643040
Camera1.cy: 255.313989
Camera1.k1: 0.262383
Camera1.k2: -0.953104
Camera1.p1: -0.005358
Camera1.p2: 0.002628
Camera1.k3: 1.163314
Camera.width: 640
Camera.height: 480
Camera.fps: 30
Camera.RGB: 1
RGBD.DepthMapFactor: 5000.0
Tcw: !!opencv-matrix
  rows: 2
  cols: 2
  dt: f
  data: [1, 0, 0, 1]
tracking:
  max_lost_seconds: 2.5
)";

TEST(Settings, AcceptsOrbSlam3FileUnchanged) {
  const Settings s = parse_settings(kOrbSlam3, "TUM1.yaml");
  EXPECT_DOUBLE_EQ(s.camera.camera.fx, 517.306408);
  EXPECT_DOUBLE_EQ(s.camera.camera.k3, 1.163314);
  EXPECT_EQ(s.camera.camera.width, 640);
  EXPECT_DOUBLE_EQ(*s.camera.depth_map_factor, 5000.0);
  double v = 1.0;
  read_option(s.section("tracking"), "tracking", "max_lost_seconds", v, s.file);
  EXPECT_DOUBLE_EQ(v, 2.5);
  int untouched = 7;
  read_option(s.section("tracking"), "tracking", "absent", untouched, s.file);
  EXPECT_EQ(untouched, 7);
}

TEST(Settings, OrbSlam2KeysToo) {
  const Settings s = parse_settings("Camera.fx: 500\nCamera.fy: 500\nCamera.cx: 320\nCamera.cy: 240\n"
                                    "Camera.width: 640\nCamera.height: 480\nDepthMapFactor: 1000\n", "s2.yaml");
  EXPECT_DOUBLE_EQ(s.camera.camera.fx, 500);
  EXPECT_DOUBLE_EQ(*s.camera.depth_map_factor, 1000);
}

// The notes of a minimal valid file with `extra` appended (its first line is line 7).
std::vector<std::string> notes_of(const std::string& extra) {
  return parse_settings(
             "Camera1.fx: 500\nCamera1.fy: 500\nCamera1.cx: 320\nCamera1.cy: 240\nCamera.width: 640\n"
             "Camera.height: 480\n" +
                 extra,
             "s.yaml")
      .notes;
}

TEST(Settings, UnreadKeysThatLookMeantAreNoted) {
  EXPECT_EQ(notes_of("ORBextractor.nFeature: 1500\n"),
            std::vector<std::string>{"s.yaml:7: key 'ORBextractor.nFeature': not a key wardmap reads, so it changes "
                                     "nothing (did you mean 'ORBextractor.nFeatures'?)"});
  EXPECT_EQ(
      notes_of("Camera2.fx: 500\nCamera2.fy: 500\n"),
      std::vector<std::string>{"s.yaml:7: key 'Camera2.fx': a stereo rig's second camera (Camera2.*) is not read; "
                               "wardmap runs monocular or RGB-D on Camera1"});
  EXPECT_EQ(notes_of("Camera.imageScale: 0.5\n").size(), 1u);
  EXPECT_EQ(notes_of("Camera.newWidth: 600\n").size(), 1u);
  // ORB-SLAM3's keys that change nothing here, or are ORB-SLAM2's names of keys read: no note.
  EXPECT_EQ(notes_of("Camera.imageScale: 1.0\nCamera.newWidth: 640\nViewer.PointSize: 2\nCamera1.k4: 0\n"
                     "File.version: \"1.0\"\nIMU.Frequency: 200\nCamera.bf: 40\nThDepth: 40\n"
                     "Tbc: !!opencv-matrix\n  rows: 1\n  cols: 1\n  dt: f\n  data: [1]\n"),
            std::vector<std::string>{});
  EXPECT_TRUE(parse_settings(kOrbSlam3, "TUM1.yaml").notes.empty());
  // A section written otherwise would have all its keys ignored: an error.
  std::string error;
  try {
    notes_of("Tracking:\n  max_depth: 3\n");
  } catch (const InputError& e) {
    error = e.what();
  }
  EXPECT_EQ(error,
            "s.yaml:7: key 'Tracking': not a section wardmap reads (did you mean 'tracking'?); its keys would all be "
            "ignored");
}

TEST(Settings, ErrorsNameTheKey) {
  EXPECT_EQ(error_of("Camera1.fy: 1\nCamera1.cx: 1\nCamera1.cy: 1\n"), "s.yaml: missing key 'Camera1.fx' (camera calibration)");
  EXPECT_EQ(error_of("Camera1.fx: abc\n"), "s.yaml:1: key 'Camera1.fx': expected a number, got 'abc'");
  EXPECT_EQ(error_of("Camera.type: \"KannalaBrandt8\"\n"),
            "s.yaml: key 'Camera.type': 'KannalaBrandt8' is not supported (allowed: PinHole)");
  // A calibration the camera model refuses is reported at the key (and line) holding the value.
  const std::string camera = "Camera1.fx: 5\nCamera1.fy: 1\nCamera.cx: 1\nCamera1.cy: 1\nCamera.width: 9\nCamera.height: 9\n";
  const auto with = [&](const std::string& key, const std::string& value) {
    std::string text = camera;
    const size_t at = text.find(key + ": ");
    const size_t end = text.find('\n', at);
    return text.replace(at, end - at, key + ": " + value);
  };
  EXPECT_EQ(error_of(with("Camera1.fx", "-5")), "s.yaml:1: key 'Camera1.fx': camera calibration: fx must be positive (got -5)");
  EXPECT_EQ(error_of(with("Camera1.fy", "0")), "s.yaml:2: key 'Camera1.fy': camera calibration: fy must be positive (got 0)");
  EXPECT_EQ(error_of(with("Camera.cx", "12")),
            "s.yaml:3: key 'Camera.cx': camera calibration: cx must lie inside the image width 9 (got 12)");
  EXPECT_EQ(error_of(with("Camera1.cy", "-1")),
            "s.yaml:4: key 'Camera1.cy': camera calibration: cy must lie inside the image height 9 (got -1)");
  EXPECT_EQ(error_of(with("Camera.height", "0")),
            "s.yaml:6: key 'Camera.height': camera calibration: image size must be positive (got 9x0)");
  EXPECT_EQ(error_of(camera + "Camera1.k1: .nan\n"), "s.yaml: camera calibration: distortion coefficients must be finite");
  // ... and when an override gave the value, at that --set.
  std::string blamed;
  try {
    const std::vector<SettingOverride> set = {parse_setting_override("Camera1.fx=-2")};
    blame_overrides(set, [&] { parse_settings(camera, "s.yaml", set); });
  } catch (const InputError& ex) {
    blamed = ex.what();
  }
  EXPECT_EQ(blamed, "--set Camera1.fx=-2: key 'Camera1.fx': camera calibration: fx must be positive (got -2)");
  EXPECT_EQ(error_of("semantics:\n  association: {chains: 2}\nsemantics:\n  groups: {size: 4}\n"),
            "s.yaml:3: key 'semantics' appears twice (lines 1 and 3); merge the two, the second would be ignored");
  EXPECT_EQ(error_of("a:\n  - b: {c: 1, c: 2}\n"),
            "s.yaml:2: key 'a.b.c' appears twice (lines 2 and 2); merge the two, the second would be ignored");
  EXPECT_NE(error_of("a: [1, 2\n").find("s.yaml:2: YAML syntax error"), std::string::npos) << error_of("a: [1, 2\n");
  const Settings s = parse_settings(kOrbSlam3, "t.yaml");
  std::string e;
  try {
    bool flag;
    read_option(s.root, "tracking", "max_lost_seconds", flag, "t.yaml");
    read_option(s.section("tracking"), "tracking", "max_lost_seconds", flag, "t.yaml");
  } catch (const InputError& ex) {
    e = ex.what();
  }
  EXPECT_EQ(e, "t.yaml:23: key 'tracking.max_lost_seconds': expected true or false, got '2.5'");
  EXPECT_THROW(check_range(5, 0, 1, "tracking.ratio", "t.yaml"), InputError);
}

// The calibration's image size against the sequence's, blamed on the --set that changed it.
TEST(Settings, CalibrationSizeChecked) {
  PinholeCamera c = pinhole(640, 480, 500, 320, 240);
  EXPECT_EQ(fit_calibration_size(c, 640, 480, "s.yaml"), std::nullopt);
  const auto error_of = [&](const std::vector<SettingOverride>& set) {
    try {
      PinholeCamera copy = c;
      fit_calibration_size(copy, 64, 480, "s.yaml", set);
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("(no error)");
  };
  EXPECT_EQ(error_of({}), "s.yaml: Camera.width/height 640x480 do not match the sequence's images 64x480");
  EXPECT_EQ(error_of({parse_setting_override("Camera.width=640")}),
            "--set Camera.width=640: Camera.width/height 640x480 do not match the sequence's images 64x480");
  // A --set of the size that agrees with the sequence is not the one to blame.
  EXPECT_EQ(error_of({parse_setting_override("Camera.height=480")}),
            "s.yaml: Camera.width/height 640x480 do not match the sequence's images 64x480");
}

// ORB-SLAM3's KITTI03.yaml says 1241x376 for 1242x375 images: a size within 2 % of each side is
// taken from the images, with a note; the principal point must still lie inside.
TEST(Settings, CalibrationSizeOffByAPixelIsTakenFromTheImages) {
  PinholeCamera c = pinhole(1241, 376, 721.5377, 609.5593, 172.854);
  const auto note = fit_calibration_size(c, 1242, 375, "KITTI03.yaml");
  ASSERT_TRUE(note.has_value());
  EXPECT_EQ(*note,
            "KITTI03.yaml: Camera.width/height 1241x376 differ slightly from the sequence's images 1242x375 (by at "
            "most 2 % or 2 pixels a side): the images' size is used");
  EXPECT_EQ(c.width, 1242);
  EXPECT_EQ(c.height, 375);
  // 3 % off: a calibration for another resolution.
  c.width = 1280;
  EXPECT_THROW(fit_calibration_size(c, 1242, 375, "KITTI03.yaml"), InputError);
  EXPECT_EQ(c.width, 1280);  // left as it was
  // Close, but the principal point falls outside the images.
  c.width = 640;
  c.height = 480;
  c.cx = 639.5;
  c.cy = 240;
  try {
    fit_calibration_size(c, 630, 480, "s.yaml");
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()),
              "s.yaml: Camera.width/height 640x480 are close to the sequence's images 630x480, but on them: cx must "
              "lie inside the image width 630 (got 639.5)");
  }
}

// A settings file's camera against the calibration the sequence carries: within half a percent of
// focal length and 2 pixels of principal point they agree; further off, or with other distortion,
// a note gives both and says which is used.
TEST(Settings, CalibrationDisagreementWithTheSequences) {
  const PinholeCamera carried = pinhole(640, 480, 585, 320, 240);
  PinholeCamera used = carried;
  used.fx = 587.5;  // 0.43 % off
  used.cy = 241.9;
  EXPECT_EQ(calibration_disagreement(used, "s.yaml", carried, "camera-intrinsics.txt"), std::nullopt);
  used.fx = 588.0;  // 0.51 % off
  auto note = calibration_disagreement(used, "s.yaml", carried, "camera-intrinsics.txt");
  ASSERT_TRUE(note.has_value());
  EXPECT_EQ(*note,
            "s.yaml: the camera (fx 588.000 fy 585.000 cx 320.000 cy 241.900) differs from the calibration the "
            "sequence carries (camera-intrinsics.txt: fx 585.000 fy 585.000 cx 320.000 cy 240.000); the settings' "
            "camera is used");
  used = carried;
  used.cx = 322.5;
  EXPECT_TRUE(calibration_disagreement(used, "s.yaml", carried, "c.txt").has_value());
  // The same pinhole with another distortion: both distortions are shown.
  used = carried;
  used.k1 = 0.262383;
  note = calibration_disagreement(used, "TUM1.yaml", carried, "c.txt");
  ASSERT_TRUE(note.has_value());
  EXPECT_NE(note->find("(fx 585.000 fy 585.000 cx 320.000 cy 240.000 k1 0.262383 k2 0 p1 0 p2 0 k3 0)"),
            std::string::npos)
      << *note;
  EXPECT_NE(note->find("(c.txt: fx 585.000 fy 585.000 cx 320.000 cy 240.000 k1 0 k2 0 p1 0 p2 0 k3 0)"),
            std::string::npos)
      << *note;
  used.k1 = 0.0005;  // within 1e-3
  EXPECT_EQ(calibration_disagreement(used, "s.yaml", carried, "c.txt"), std::nullopt);
}

// fit_settings_to_sequence: the notes join the settings' notes, a --set of the camera named beside
// the file; a depth factor other than the format's is noted unless the file is the sequence's own.
TEST(Settings, FitSettingsToSequenceNotesAnotherCalibrationAndDepthFactor) {
  const auto dir = test::scratch_dir();
  const auto file = dir / "s.yaml";
  std::ofstream(file) << "Camera1.fx: 50.0\nCamera1.fy: 50.0\nCamera1.cx: 32.0\nCamera1.cy: 24.0\n"
                        "Camera.width: 64\nCamera.height: 48\nRGBD.DepthMapFactor: 1000.0\n";
  SequenceInfo info;
  info.kind = DatasetKind::SevenScenes;
  info.root = dir / "seq";
  info.width = 64;
  info.height = 48;
  info.has_depth = true;
  info.depth_factor = 1000.0;
  info.calibration = load_settings(file).camera.camera;
  info.calibration_source = (info.root / "camera-intrinsics.txt").string();
  Settings s = load_settings(file);
  fit_settings_to_sequence(s, info, {});
  EXPECT_TRUE(s.notes.empty());
  const std::vector<SettingOverride> set = {parse_setting_override("Camera1.fx=55"),
                                            parse_setting_override("RGBD.DepthMapFactor=5000")};
  s = load_settings(file, set);
  fit_settings_to_sequence(s, info, set);
  ASSERT_EQ(s.notes.size(), 2u);
  EXPECT_EQ(s.notes[0].rfind(file.string() + " with --set Camera1.fx=55: the camera (fx 55.000 fy 50.000", 0), 0u)
      << s.notes[0];
  EXPECT_EQ(s.notes[1], file.string() +
                            ": RGBD.DepthMapFactor 5000 differs from the 1000 raw units per metre of the 7-Scenes "
                            "format; the settings' factor is used");
  // Within 1 %, or no depth: nothing.
  EXPECT_EQ(depth_factor_disagreement(1005, "s.yaml", 1000, "7-Scenes"), std::nullopt);
  info.has_depth = false;
  s = load_settings(file, {set[1]});
  fit_settings_to_sequence(s, info, {set[1]});
  EXPECT_TRUE(s.notes.empty());
  // The sequence's own settings.yaml (a recording in TUM's layout with its own factor).
  info.has_depth = true;
  std::filesystem::create_directories(info.root);
  std::filesystem::copy_file(file, info.root / "settings.yaml");
  s = load_settings(info.root / "settings.yaml", {set[1]});
  fit_settings_to_sequence(s, info, {set[1]});
  EXPECT_TRUE(s.notes.empty());
}

TEST(Settings, ShippedFilesLoad) {
  const auto dir = test::source_dir() / "data" / "settings";
  int n = 0;
  for (const auto& e : std::filesystem::directory_iterator(dir)) {
    if (e.path().extension() != ".yaml") continue;
    EXPECT_NO_THROW(load_settings(e.path())) << e.path();
    ++n;
  }
  EXPECT_GE(n, 8);
  const Settings k = load_settings(dir / "KITTI03.yaml");
  EXPECT_DOUBLE_EQ(k.camera.camera.fx, 721.5377);
  EXPECT_EQ(k.camera.camera.width, 1242);
  const Settings s7 = load_settings(dir / "7Scenes.yaml");
  EXPECT_DOUBLE_EQ(s7.camera.camera.fx, 585.0);
  EXPECT_DOUBLE_EQ(*s7.camera.depth_map_factor, 1000.0);
  EXPECT_EQ(suggest_settings_name("KITTI odometry", "x", 1242), "KITTI03.yaml");
}

}  // namespace
}  // namespace wardmap::slam::io
