#include "slam/front/front_options.h"

#include <gtest/gtest.h>

#include "slam/core/errors.h"
#include "slam/io/settings.h"
#include "tests/support/test_support.h"

namespace wardmap::slam {

TEST(FrontOptions, ShippedSettingsLoadOrbKeys) {
  const io::Settings s = io::load_settings(test::source_dir() / "data/settings/7Scenes.yaml");
  const FrontOptions o = load_front_options(s);
  EXPECT_EQ(o.orb.n_features, 1000);
  EXPECT_DOUBLE_EQ(o.orb.scale_factor, 1.2);
  EXPECT_EQ(o.orb.n_levels, 8);
  EXPECT_EQ(o.orb.ini_th_fast, 20);
  EXPECT_EQ(o.orb.min_th_fast, 7);
}

const char* kBase =
    "Camera.type: \"PinHole\"\nCamera1.fx: 500\nCamera1.fy: 500\nCamera1.cx: 320\nCamera1.cy: 240\n"
    "Camera.width: 640\nCamera.height: 480\n";

TEST(FrontOptions, TrackingAndMappingSectionsOverrideDefaults) {
  const std::string text = std::string(kBase) +
                           "ORBextractor.nFeatures: 1500\ntracking:\n  short_term_seconds: 1.5\n  match_th_low: 40\n"
                           "  pose_solver: lm\nmapping:\n  ba_max_keyframes: 7\n  keyframe_culling: false\n  inline_busy_seconds: 0.05\n  min_parallax_deg_mono: 2.5\n"
                           "  sequence_time_for_mapper: false\n  abort_ba_when_behind: false\n  ba_max_keyframes_mono: 15\n";
  const FrontOptions o = load_front_options(io::parse_settings(text, "t.yaml"));
  EXPECT_EQ(o.orb.n_features, 1500);
  EXPECT_DOUBLE_EQ(o.tracking.short_term_seconds, 1.5);
  EXPECT_EQ(o.matcher.th_low, 40);
  EXPECT_EQ(o.mapping.ba_max_keyframes, 7);
  EXPECT_FALSE(o.mapping.keyframe_culling);
  EXPECT_DOUBLE_EQ(o.mapping.inline_busy_seconds, 0.05);
  EXPECT_DOUBLE_EQ(o.mapping.min_parallax_deg_mono, 2.5);
  EXPECT_FALSE(o.mapping.sequence_time_for_mapper);
  EXPECT_TRUE(FrontOptions{}.mapping.sequence_time_for_mapper);
  EXPECT_FALSE(o.mapping.abort_ba_when_behind);
  EXPECT_EQ(o.mapping.ba_max_keyframes_mono, 15);
  EXPECT_EQ(o.mapping.ba_max_fixed_keyframes_mono, FrontOptions{}.mapping.ba_max_fixed_keyframes_mono);
  EXPECT_EQ(o.tracking.pose_rounds, FrontOptions{}.tracking.pose_rounds);
  EXPECT_EQ(o.tracking.pose_solver, "lm");
  EXPECT_EQ(FrontOptions{}.tracking.pose_solver, "ceres");
}

TEST(FrontOptions, OrbSlamStereoKeysSetTheVirtualBaselineAndCloseDepth) {
  const std::string text = std::string(kBase) + "Stereo.b: 0.07\nStereo.ThDepth: 40.0\n";
  const FrontOptions o = load_front_options(io::parse_settings(text, "t.yaml"));
  EXPECT_DOUBLE_EQ(o.tracking.virtual_baseline, 0.07);
  EXPECT_NEAR(o.tracking.close_depth, 2.8, 1e-12);
  const FrontOptions p = load_front_options(
      io::parse_settings(text + "tracking:\n  close_depth: 2.0\n  virtual_baseline: 0.1\n", "t.yaml"));
  EXPECT_DOUBLE_EQ(p.tracking.close_depth, 2.0);
  EXPECT_DOUBLE_EQ(p.tracking.virtual_baseline, 0.1);
}

TEST(FrontOptions, InvalidValuesNameTheKey) {
  const auto expect_error = [](const std::string& extra, const std::string& key) {
    try {
      load_front_options(io::parse_settings(std::string(kBase) + extra, "bad.yaml"));
      FAIL() << "no error for " << extra;
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(key), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find("bad.yaml"), std::string::npos) << e.what();
    }
  };
  expect_error("ORBextractor.scaleFactor: 0.9\n", "ORBextractor.scaleFactor");
  expect_error("ORBextractor.iniThFAST: 5\nORBextractor.minThFAST: 9\n", "ORBextractor.minThFAST");
  expect_error("tracking:\n  match_th_high: 20\n", "tracking.match_th_high");
  expect_error("tracking:\n  pose_rounds: abc\n", "tracking.pose_rounds");
  expect_error("tracking:\n  pose_solver: gauss\n", "tracking.pose_solver");
  expect_error("mapping:\n  redundant_ratio: 1.5\n", "mapping.redundant_ratio");
  expect_error("mapping:\n  inline_busy_seconds: -0.1\n", "mapping.inline_busy_seconds");
  expect_error("mapping:\n  min_parallax_deg_mono: 95\n", "mapping.min_parallax_deg_mono");
  expect_error("mapping:\n  ba_max_keyframes_mono: 0\n", "mapping.ba_max_keyframes_mono");
}

}  // namespace wardmap::slam
