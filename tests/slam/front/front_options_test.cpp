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
                           "  pose_solver: lm\nmapping:\n  ba_max_keyframes: 7\n  keyframe_culling: false\n  min_busy_seconds: 0.05\n  min_parallax_deg_mono: 2.5\n"
                           "  sequence_time_for_mapper: false\n  abort_ba_when_behind: false\n  ba_max_keyframes_mono: 15\n";
  const FrontOptions o = load_front_options(io::parse_settings(text, "t.yaml"));
  EXPECT_EQ(o.orb.n_features, 1500);
  EXPECT_DOUBLE_EQ(o.tracking.short_term_seconds, 1.5);
  EXPECT_EQ(o.matcher.th_low, 40);
  EXPECT_EQ(o.mapping.ba_max_keyframes, 7);
  EXPECT_FALSE(o.mapping.keyframe_culling);
  EXPECT_EQ(load_front_options(io::parse_settings(std::string(kBase) + "tracking:\ntracking.pose_solver: lm\n", "e.yaml"))
                .tracking.pose_solver,
            "lm");
  EXPECT_DOUBLE_EQ(o.mapping.min_busy_seconds, 0.05);
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

// The optical flow is on by default in monocular (under its time budget), off in RGB-D; each mode
// has its own key.
TEST(FrontOptions, FlowIsOnInMonocularByDefaultAndHasAKeyPerMode) {
  const FrontOptions d = load_front_options(io::parse_settings(kBase, "t.yaml"));
  EXPECT_FALSE(d.tracking.flow(false));
  EXPECT_TRUE(d.tracking.flow(true));
  const FrontOptions rgbd = load_front_options(io::parse_settings(
      std::string(kBase) + "tracking:\n  flow_extend: true\n  flow_extend_mono: false\n", "t.yaml"));
  EXPECT_TRUE(rgbd.tracking.flow(false));
  EXPECT_FALSE(rgbd.tracking.flow(true));
  // Its time budget, per mode too (the targets at 640x480 by default).
  EXPECT_DOUBLE_EQ(d.tracking.flow_budget_ms_for(true), 10.0);
  EXPECT_DOUBLE_EQ(d.tracking.flow_budget_ms_for(false), 15.0);
  const FrontOptions budget = load_front_options(
      io::parse_settings(std::string(kBase) + "tracking:\n  flow_budget_ms_mono: 0\n  flow_budget_frames: 10\n", "t.yaml"));
  EXPECT_DOUBLE_EQ(budget.tracking.flow_budget_ms_for(true), 0.0);
  EXPECT_EQ(budget.tracking.flow_budget_frames, 10);
}

// The keyframe ratio test counts the reference keyframe's points seen by 2 keyframes in RGB-D (a
// point made from depth is whole at once), by 3 in monocular (ORB-SLAM's count); a key per mode.
TEST(FrontOptions, ReferencePointsObservationsHaveAKeyPerMode) {
  const FrontOptions d = load_front_options(io::parse_settings(kBase, "t.yaml"));
  EXPECT_EQ(d.tracking.keyframe_ref_min_observations, 2);
  EXPECT_EQ(d.tracking.keyframe_ref_min_observations_mono, 3);
  const FrontOptions o = load_front_options(io::parse_settings(
      std::string(kBase) + "tracking:\n  keyframe_ref_min_observations: 3\n  keyframe_ref_min_observations_mono: 2\n",
      "t.yaml"));
  EXPECT_EQ(o.tracking.keyframe_ref_min_observations, 3);
  EXPECT_EQ(o.tracking.keyframe_ref_min_observations_mono, 2);
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

TEST(FrontOptions, OrbSlam2StereoKeysToo) {
  // ORB-SLAM2's TUM1.yaml: Camera.bf is the baseline times fx.
  const FrontOptions o =
      load_front_options(io::parse_settings(std::string(kBase) + "Camera.bf: 40.0\nThDepth: 40.0\n", "t.yaml"));
  EXPECT_DOUBLE_EQ(o.tracking.virtual_baseline, 0.08);
  EXPECT_NEAR(o.tracking.close_depth, 3.2, 1e-12);
  const auto error_of = [](const std::string& extra) {
    try {
      load_front_options(io::parse_settings(std::string(kBase) + extra, "t.yaml"));
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("(no error)");
  };
  EXPECT_EQ(error_of("Stereo.b: -0.08\n"), "t.yaml:8: key 'Stereo.b': must be positive, got -0.080000");
  EXPECT_EQ(error_of("Camera.bf: 0\n"), "t.yaml:8: key 'Camera.bf': must be positive, got 0.000000");
  EXPECT_EQ(error_of("Stereo.b: 0.08\nThDepth: -1\n"), "t.yaml:9: key 'ThDepth': must be positive, got -1.000000");
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
  expect_error("tracking:\n  flow_max_age: 0\n", "tracking.flow_max_age");
  expect_error("tracking:\n  flow_extend: maybe\n", "tracking.flow_extend");
  expect_error("tracking:\n  flow_extend_mono: 2\n", "tracking.flow_extend_mono");
  expect_error("tracking:\n  flow_budget_ms_mono: -1\n", "tracking.flow_budget_ms_mono");
  expect_error("tracking:\n  flow_budget_frames: 0\n", "tracking.flow_budget_frames");
  expect_error("tracking:\n  keyframe_ref_min_observations: 0\n", "tracking.keyframe_ref_min_observations");
  expect_error("tracking:\n  init_still_px: -1\n", "tracking.init_still_px");
  expect_error("tracking:\n  keyframe_still_px: -0.5\n", "tracking.keyframe_still_px");
  expect_error("tracking:\n  discard_submap_keyframes: -1\n", "tracking.discard_submap_keyframes");
  expect_error("mapping:\n  redundant_ratio: 1.5\n", "mapping.redundant_ratio");
  expect_error("mapping:\n  min_busy_seconds: -0.1\n", "mapping.min_busy_seconds");
  expect_error("mapping:\n  min_parallax_deg_mono: 95\n", "mapping.min_parallax_deg_mono");
  expect_error("mapping:\n  ba_max_keyframes_mono: 0\n", "mapping.ba_max_keyframes_mono");
}

// A misspelt or misplaced key is an error naming it (and the key it probably meant), not a
// silently ignored setting.
TEST(FrontOptions, UnknownKeysInTheSectionsAreErrors) {
  const auto error_of = [](const std::string& extra) -> std::string {
    try {
      load_front_options(io::parse_settings(std::string(kBase) + extra, "bad.yaml"));
    } catch (const InputError& e) {
      return e.what();
    }
    return "";
  };
  const std::string typo = error_of("tracking:\n  pose_solvr: lm\n");
  EXPECT_NE(typo.find("'tracking.pose_solvr'"), std::string::npos) << typo;
  EXPECT_NE(typo.find("did you mean 'tracking.pose_solver'"), std::string::npos) << typo;
  EXPECT_NE(typo.find("bad.yaml"), std::string::npos) << typo;
  // A mapping key in the tracking section.
  const std::string misplaced = error_of("tracking:\n  redundant_ratio: 0.8\n");
  EXPECT_NE(misplaced.find("'tracking.redundant_ratio'"), std::string::npos) << misplaced;
  EXPECT_NE(error_of("mapping:\n  nonsense: 1\n").find("'mapping.nonsense'"), std::string::npos);
  EXPECT_NE(error_of("mapping: 3\n").find("expected a section"), std::string::npos);
  EXPECT_EQ(error_of("mapping:\n"), "");  // an empty section
  // ORB-SLAM3 keys outside wardmap's sections are left alone (an ORB-SLAM3 file has many).
  EXPECT_EQ(error_of("Viewer.KeyFrameSize: 0.05\n"), "");
}

// The documentation writes keys as `tracking.pose_solver`; written that way at the top level of a
// settings file they act as in their section.
TEST(FrontOptions, DottedKeysActAsInTheirSection) {
  const FrontOptions o = load_front_options(io::parse_settings(
      std::string(kBase) + "tracking.pose_solver: lm\nmapping.ba_max_keyframes: 7\nmapping:\n  keyframe_culling: false\n",
      "dotted.yaml"));
  EXPECT_EQ(o.tracking.pose_solver, "lm");
  EXPECT_EQ(o.mapping.ba_max_keyframes, 7);
  EXPECT_FALSE(o.mapping.keyframe_culling);
  EXPECT_EQ(load_front_options(io::parse_settings(std::string(kBase) + "tracking:\ntracking.pose_solver: lm\n", "e.yaml"))
                .tracking.pose_solver,
            "lm");
  try {
    io::parse_settings(std::string(kBase) + "tracking.pose_solver: lm\ntracking:\n  pose_solver: ceres\n", "twice.yaml");
    FAIL() << "a key set twice was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("'tracking.pose_solver' is set twice"), std::string::npos) << e.what();
  }
  EXPECT_THROW(io::parse_settings(std::string(kBase) + "tracking: 3\ntracking.pose_solver: lm\n", "t.yaml"), InputError);
}

// `wardmap run --set KEY=VALUE`: an override replaces the file's value (nested or dotted), adds a key
// the file lacks, and sets ORB-SLAM3's dotted keys as the keys they are; the last of a key wins.
TEST(FrontOptions, CommandLineOverridesReplaceTheFilesKeys) {
  const std::string file = std::string(kBase) + "ORBextractor.nFeatures: 1000\ntracking:\n  pose_solver: ceres\n" +
                           "mapping.ba_max_keyframes: 7\n";
  const std::vector<io::SettingOverride> set = {
      io::parse_setting_override("tracking.pose_solver=lm"), io::parse_setting_override("mapping.ba_max_keyframes=9"),
      io::parse_setting_override("mapping.keyframe_culling=false"), io::parse_setting_override("ORBextractor.nFeatures=1500"),
      io::parse_setting_override("mapping.ba_max_keyframes=11")};
  const FrontOptions o = load_front_options(io::parse_settings(file, "o.yaml", set));
  EXPECT_EQ(o.tracking.pose_solver, "lm");
  EXPECT_EQ(o.mapping.ba_max_keyframes, 11);
  EXPECT_FALSE(o.mapping.keyframe_culling);
  EXPECT_EQ(o.orb.n_features, 1500);
  const FrontOptions plain = load_front_options(io::parse_settings(file, "o.yaml"));
  EXPECT_EQ(plain.tracking.pose_solver, "ceres");
  EXPECT_EQ(plain.mapping.ba_max_keyframes, 7);
  EXPECT_EQ(plain.orb.n_features, 1000);
}

// A wrong override is reported as the --set that gave it, not as the file.
TEST(FrontOptions, CommandLineOverrideErrorsNameTheSet) {
  const auto error_of = [](const std::string& text) {
    try {
      const std::vector<io::SettingOverride> set = {io::parse_setting_override(text)};
      io::blame_overrides(set, [&] { load_front_options(io::parse_settings(kBase, "o.yaml", set)); });
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("(no error)");
  };
  EXPECT_EQ(error_of("tracking.pose_solvr=lm"),
            "--set tracking.pose_solvr=lm: key 'tracking.pose_solvr': not a key of section 'tracking' (did you mean "
            "'tracking.pose_solver'?)");
  EXPECT_EQ(error_of("tracking.flow_extend_mono=maybe"),
            "--set tracking.flow_extend_mono=maybe: key 'tracking.flow_extend_mono': expected true or false, got 'maybe'");
  EXPECT_EQ(error_of("ORBextractor.nFeatures=-3"),
            "--set ORBextractor.nFeatures=-3: key 'ORBextractor.nFeatures': must be in [50, 20000], got -3");
  EXPECT_EQ(error_of("tracking.pose_solver"), "--set: 'tracking.pose_solver': expected KEY=VALUE (e.g. tracking.flow_extend_mono=false)");
  EXPECT_EQ(error_of("=lm"), "--set: '=lm': the key before '=' is empty");
  EXPECT_EQ(error_of("tracking.pose_solver="), "--set: 'tracking.pose_solver=': the value after '=' is empty");
  EXPECT_EQ(error_of("mapping=3"), "--set: 'mapping=3': 'mapping' is a whole section; set its keys one by one (mapping.KEY=VALUE)");
  try {
    io::parse_settings(std::string(kBase) + "tracking:\n  pose_solver: lm\n", "o.yaml",
                       {io::parse_setting_override("tracking.pose_solver.x=1")});
    FAIL() << "a key under a value was accepted";
  } catch (const InputError& e) {
    EXPECT_STREQ(e.what(), "--set: key 'tracking.pose_solver.x': 'tracking.pose_solver' is not a section");
  }
  EXPECT_NE(error_of("tracking.pose_solver=[lm").find("--set: 'tracking.pose_solver=[lm': the value is not valid YAML"),
            std::string::npos);
  // A top-level key nothing reads would change nothing: refused, with the nearest one read.
  EXPECT_EQ(error_of("ORBextractor.nFeature=1500"),
            "--set: 'ORBextractor.nFeature=1500': 'ORBextractor.nFeature' is not a key wardmap reads (did you mean "
            "'ORBextractor.nFeatures'?); its own keys are tracking.*, mapping.*, semantics.* and detection.*");
  EXPECT_EQ(error_of("Viewer.KeyFrameSize=0.05").find("--set: 'Viewer.KeyFrameSize=0.05': 'Viewer.KeyFrameSize' is "
                                                       "not a key wardmap reads"),
            0u);
  EXPECT_EQ(error_of("Camera1.fx=400"), "(no error)");
  EXPECT_EQ(error_of("Stereo.ThDepth=40"), "(no error)");
  // ORB-SLAM2's name of a key the file writes under ORB-SLAM3's would be read second, so unused.
  EXPECT_EQ(error_of("Camera.fx=400"),
            "--set: 'Camera.fx=400': the settings file writes this key as 'Camera1.fx', which is read first; set that one");
  EXPECT_DOUBLE_EQ(io::parse_settings(std::string(kBase) + "DepthMapFactor: 1000\n", "d.yaml",
                                      {io::parse_setting_override("DepthMapFactor=5000")})
                       .camera.depth_map_factor.value_or(0),
                   5000);
  // An error about a key the override did not touch still names the file.
  try {
    io::blame_overrides({io::parse_setting_override("tracking.pose_solver=lm")}, [] {
      load_front_options(io::parse_settings(std::string(kBase) + "tracking:\n  max_lost_seconds: x\n", "o.yaml"));
    });
    FAIL() << "a bad value was accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), "o.yaml") << e.what();
  }
}

}  // namespace wardmap::slam
