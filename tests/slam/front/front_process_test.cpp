// End to end: a short synthetic RGB-D sequence rendered by `wardmap synth`, tracked by the
// front-process, evaluated with the project's ATE (SE(3) alignment).
#include "slam/front/front_process.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>

#include "slam/eval/trajectory_eval.h"
#include "slam/io/sequence.h"
#include "slam/io/settings.h"
#include "slam/place/vocabulary.h"
#include "tests/support/test_support.h"

namespace wardmap::slam {

namespace fs = std::filesystem;

namespace {

// The wardmap executable ($WARDMAP_BIN overrides the build tree's).
fs::path wardmap_binary() {
  if (const char* v = std::getenv("WARDMAP_BIN"); v && *v) return v;
  return test::binary_dir() / "apps" / "wardmap";
}

// `wardmap synth ARGS --out SEQ`; a failure carries the command's output.
::testing::AssertionResult render(const fs::path& seq, const std::string& args) {
  std::string log;
  if (test::run_command(wardmap_binary().string() + " synth " + args + " --out " + seq.string(), &log) == 0)
    return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure() << "wardmap synth " << args << ":\n" << log;
}

// A rendered sequence's reader, its depth scaled by the sequence's settings.
std::unique_ptr<io::SequenceReader> open_with_depth(const fs::path& seq, const io::Settings& settings) {
  io::ReaderOptions ro;
  ro.depth_factor = settings.camera.depth_map_factor;
  return io::open_sequence(seq, ro);
}

}  // namespace

TEST(FrontProcess, TracksASyntheticRgbdAisle) {
  const fs::path bin = wardmap_binary();
  if (!fs::exists(bin)) GTEST_SKIP() << "wardmap executable not built: " << bin;
  const fs::path seq = test::scratch_dir() / "aisle";
  ASSERT_TRUE(render(seq, "--scenario aisle_straight --variant slow --seed 1 --frames 90"));

  const io::Settings settings = io::load_settings(seq / "settings.yaml");
  const FrontOptions options = load_front_options(settings);
  auto reader = open_with_depth(seq, settings);
  ASSERT_EQ(reader->size(), 90u);

  FrontProcess front(options, settings.camera.camera);
  int tracked = 0, keyframes = 0;
  for (size_t i = 0; i < reader->size(); ++i) {
    const FrameResult r = front.process(reader->read(i));
    tracked += r.tracked ? 1 : 0;
    keyframes += r.keyframe ? 1 : 0;
    EXPECT_TRUE(r.tracked) << "frame " << i << " " << to_string(r.state);
  }
  EXPECT_EQ(tracked, 90);
  EXPECT_GE(keyframes, 2);
  EXPECT_GT(front.submap().num_map_points(), 300u);

  const Trajectory est = front.trajectory();
  ASSERT_EQ(est.size(), 90u);
  const Trajectory& gt = reader->ground_truth();
  const auto pairs = eval::associate(gt, est, eval::AssociationOptions{});
  const eval::AteResult ate = eval::compute_ate(gt, est, pairs, eval::Alignment::SE3);
  EXPECT_EQ(ate.pairs, 90u);
  EXPECT_LE(ate.stats.rmse, 0.02) << "ATE RMSE " << ate.stats.rmse << " m";
  RecordProperty("ate_rmse_m", std::to_string(ate.stats.rmse));

  // Blind frames (black, no depth): lost, then after tracking.lost_frames_to_reset a new submap; the
  // trajectory stays that of the largest submap.
  ASSERT_GT(front.submap().num_keyframes(), static_cast<size_t>(options.tracking.young_submap_keyframes));
  io::Frame blind = reader->read(89);
  blind.image.setTo(0);
  blind.depth.setTo(0);
  for (int k = 1; k <= options.tracking.lost_frames_to_reset; ++k) {
    blind.index = 89 + static_cast<size_t>(k);
    blind.timestamp += 1.0 / 30;
    const FrameResult r = front.process(blind);
    EXPECT_FALSE(r.tracked);
    EXPECT_EQ(r.new_submap, k == options.tracking.lost_frames_to_reset) << "blind frame " << k;
  }
  EXPECT_EQ(front.submaps().size(), 2u);
  EXPECT_EQ(front.trajectory().size(), 90u);

  // A submap of at most tracking.young_submap_keyframes keyframes is left at its first lost frame
  // (ORB-SLAM resets a map that small): a fresh RGB-D submap lost again at once does not hold
  // recovery up for lost_frames_to_reset frames.
  io::Frame seen = reader->read(89);
  seen.index = blind.index + 1;
  seen.timestamp = blind.timestamp + 1.0 / 30;
  ASSERT_TRUE(front.process(seen).tracked);  // RGB-D initialises the new submap from one frame
  ASSERT_EQ(front.submap().num_keyframes(), 1u);
  blind.index = seen.index + 1;
  blind.timestamp = seen.timestamp + 1.0 / 30;
  const FrameResult r = front.process(blind);
  EXPECT_FALSE(r.tracked);
  EXPECT_TRUE(r.new_submap);
  // One keyframe is too few to keep (tracking.discard_submap_keyframes, 2): the submap is discarded,
  // its frame is no longer in any trajectory, and the next submap takes its id.
  EXPECT_TRUE(r.discarded_submap);
  EXPECT_EQ(r.submap, 1);
  ASSERT_EQ(front.submaps().size(), 2u);
  EXPECT_EQ(front.submap().id(), 1);
  EXPECT_EQ(front.submaps().back().get(), &front.submap());
  EXPECT_TRUE(front.trajectory(1).empty());
  EXPECT_EQ(front.trajectory().size(), 90u);
  seen.index = blind.index + 1;
  seen.timestamp = blind.timestamp + 1.0 / 30;
  const FrameResult again = front.process(seen);
  EXPECT_TRUE(again.tracked);
  EXPECT_EQ(again.submap, 1);
  EXPECT_EQ(front.submap().num_keyframes(), 1u);
  EXPECT_EQ(front.trajectory(1).size(), 1u);

  // With 0 every submap is kept: the one-keyframe submap stays beside the new one.
  FrontOptions keep_all = options;
  keep_all.tracking.discard_submap_keyframes = 0;
  FrontProcess kept(keep_all, settings.camera.camera);
  ASSERT_TRUE(kept.process(seen).tracked);
  blind.index = seen.index + 1;
  blind.timestamp = seen.timestamp + 1.0 / 30;
  const FrameResult k = kept.process(blind);
  EXPECT_TRUE(k.new_submap);
  EXPECT_FALSE(k.discarded_submap);
  EXPECT_EQ(kept.submaps().size(), 2u);
  EXPECT_EQ(kept.trajectory(0).size(), 1u);
}

// Lost for a few blind frames, then shown an earlier part of the aisle: the motion model cannot
// help, place recognition finds the keyframes and tracking continues in the same submap.
TEST(FrontProcess, RelocalisesInTheSameSubmapAfterBlindFrames) {
  const fs::path bin = wardmap_binary();
  if (!fs::exists(bin)) GTEST_SKIP() << "wardmap executable not built: " << bin;
  const fs::path seq = test::scratch_dir() / "aisle_reloc";
  ASSERT_TRUE(render(seq, "--scenario aisle_straight --variant slow --seed 2 --frames 90"));
  const io::Settings settings = io::load_settings(seq / "settings.yaml");
  FrontOptions options = load_front_options(settings);
  // The jump is a teleport (2 s of motion in 0.1 s): lift the RGB-D motion limit on relocalisation.
  options.tracking.reloc_max_speed = 100;
  auto reader = open_with_depth(seq, settings);
  FrontProcess front(options, settings.camera.camera);
  front.set_vocabulary(std::make_shared<const place::Vocabulary>(
      place::Vocabulary::load(test::source_dir() / "data/vocabulary/orb-k10l4.bin")));
  for (size_t i = 0; i < 90; ++i) ASSERT_TRUE(front.process(reader->read(i)).tracked) << "frame " << i;
  io::Frame blind = reader->read(89);
  blind.image.setTo(0);
  blind.depth.setTo(0);
  double t = blind.timestamp;
  for (int k = 0; k < 3; ++k) {
    blind.timestamp = t += 1.0 / 30;
    EXPECT_FALSE(front.process(blind).tracked);
  }
  // Back to frame 30: 2 s earlier along the aisle, 0.3 m or more from the last pose.
  int relocalised = 0, tracked = 0;
  for (size_t i = 30; i < 50; ++i) {
    io::Frame f = reader->read(i);
    f.timestamp = t += 1.0 / 30;
    const FrameResult r = front.process(f);
    relocalised += r.relocalised ? 1 : 0;
    tracked += r.tracked ? 1 : 0;
    if (i == 30) {
      EXPECT_TRUE(r.relocalised) << to_string(r.state);
    }
    EXPECT_EQ(r.submap, 0);
    if (r.tracked) {
      const SE3 T_wc_gt = reader->ground_truth().poses[i];
      const SE3 T_wc_0 = reader->ground_truth().poses[0];
      // The first frame's pose is the map origin: compare relative to it.
      const Eigen::Vector3d expected = (T_wc_0.inverse() * T_wc_gt).translation();
      EXPECT_LT((r.T_wc.translation() - expected).norm(), 0.05) << "frame " << i;
    }
  }
  EXPECT_EQ(relocalised, 1);
  EXPECT_EQ(tracked, 20);
  EXPECT_EQ(front.submaps().size(), 1u);

  // Culled keyframes are no relocalisation candidates (ORB-SLAM's SetBadFlag erases them from its
  // keyframe database): after one more lost frame (relocalisation indexes every keyframe, the
  // mapper gets no keyframe), the place database holds exactly the submap's keyframes.
  const Submap& map = front.submap();
  const KeyFrameId made = map.keyframes().rbegin()->first + 1;  // one submap: ids 0 .. made - 1
  ASSERT_GT(made, map.num_keyframes()) << "no keyframe was culled: the check below shows nothing";
  blind.timestamp = t += 1.0 / 30;
  EXPECT_FALSE(front.process(blind).tracked);
  EXPECT_EQ(front.place_database().size(), map.num_keyframes());
  for (const auto& [id, kf] : map.keyframes()) EXPECT_TRUE(front.place_database().contains(id)) << "keyframe " << id;
}

namespace {

// Keypoints that the optical flow placed in the live keyframes (after the detected ones), observing a point.
size_t followed_keypoints(const FrontProcess& front) {
  size_t followed = 0;
  for (const auto& [id, kf] : front.submap().keyframes()) {
    if (kf->bad()) continue;
    for (size_t i = kf->features().detected(); i < kf->features().size(); ++i)
      if (kf->map_points()[i] && !kf->map_points()[i]->bad()) ++followed;
  }
  return followed;
}

}  // namespace

// The same aisle with local mapping on its own thread (what `wardmap run` uses); under
// `scripts/test.sh --tsan` this is the in-process check of the tracker / mapper locking. The optical
// flow (an option, off by default) is on here, so that the thread sanitizer also sees its reads of
// the map points the mapper writes; CliPipeline.ThreadedRgbdRunIsAccurate runs the defaults threaded.
TEST(FrontProcess, TracksWithTheMapperOnItsOwnThread) {
  const fs::path bin = wardmap_binary();
  if (!fs::exists(bin)) GTEST_SKIP() << "wardmap executable not built: " << bin;
  const fs::path seq = test::scratch_dir() / "aisle_thread";
  ASSERT_TRUE(render(seq, "--scenario aisle_left_turn --variant quick --seed 3 --frames 90"));
  const io::Settings settings = io::load_settings(seq / "settings.yaml");
  FrontOptions options = load_front_options(settings);
  options.mapping_thread = true;
  options.tracking.flow_extend = true;
  options.tracking.flow_budget_ms = 0;  // on every frame, however slow the sanitizer makes them
  auto reader = open_with_depth(seq, settings);
  FrontProcess front(options, settings.camera.camera);
  size_t max_queue = 0;
  for (size_t i = 0; i < reader->size(); ++i) {
    EXPECT_TRUE(front.process(reader->read(i)).tracked) << "frame " << i;
    max_queue = std::max(max_queue, front.mapper_queue_length());
  }
  front.finish();
  EXPECT_LE(max_queue, static_cast<size_t>(options.mapping.queue_capacity));
  EXPECT_GE(front.mapper_stats().keyframes, 2);
  EXPECT_GT(followed_keypoints(front), 0u) << "the flow followed no point into a keyframe";
  const Trajectory est = front.trajectory();
  const auto pairs = eval::associate(reader->ground_truth(), est, eval::AssociationOptions{});
  const eval::AteResult ate = eval::compute_ate(reader->ground_truth(), est, pairs, eval::Alignment::SE3);
  EXPECT_EQ(ate.pairs, 90u);
  EXPECT_LE(ate.stats.rmse, 0.02) << "ATE RMSE " << ate.stats.rmse << " m";
}

// tracking.flow_extend: map points the descriptor searches miss are followed by optical flow, so the
// keyframes hold keypoints that were never detected, observing map points. In monocular runs, whose
// keyframe rate it keeps, the points gain observations; RGB-D runs stay accurate.
TEST(FrontProcess, FlowFollowsThePointsTheDescriptorSearchesMiss) {
  const fs::path bin = wardmap_binary();
  if (!fs::exists(bin)) GTEST_SKIP() << "wardmap executable not built: " << bin;
  const fs::path seq = test::scratch_dir() / "aisle_flow";
  ASSERT_TRUE(render(seq, "--scenario aisle_straight --variant quick --seed 2 --frames 90"));
  const io::Settings settings = io::load_settings(seq / "settings.yaml");
  auto reader = open_with_depth(seq, settings);
  struct Run {
    double ate_se3 = 0;
    double observations_per_point = 0;
    size_t followed = 0;  // keypoints of the final keyframes that flow placed, observing a point
  };
  const auto run = [&](bool flow, bool mono) {
    FrontOptions options = load_front_options(settings);
    options.tracking.flow_extend = options.tracking.flow_extend_mono = flow;
    options.monocular = mono;
    FrontProcess front(options, settings.camera.camera);
    for (size_t i = 0; i < reader->size(); ++i) {
      const FrameResult f = front.process(reader->read(i));
      if (!mono) {
        EXPECT_TRUE(f.tracked) << "frame " << i;
      }
    }
    Run r;
    const Trajectory est = front.trajectory();
    const auto pairs = eval::associate(reader->ground_truth(), est, eval::AssociationOptions{});
    EXPECT_EQ(pairs.size(), 90u);
    r.ate_se3 = eval::compute_ate(reader->ground_truth(), est, pairs, eval::Alignment::SE3).stats.rmse;
    size_t points = 0, observations = 0;
    for (const auto& [id, mp] : front.submap().map_points()) {
      if (mp->bad()) continue;
      ++points;
      observations += static_cast<size_t>(mp->num_observations());
    }
    r.observations_per_point = points ? static_cast<double>(observations) / static_cast<double>(points) : 0;
    r.followed = followed_keypoints(front);
    return r;
  };
  const Run rgbd_off = run(false, false), rgbd_on = run(true, false);
  EXPECT_EQ(rgbd_off.followed, 0u);
  EXPECT_GT(rgbd_on.followed, 100u);
  EXPECT_LE(rgbd_on.ate_se3, 0.02) << "ATE RMSE " << rgbd_on.ate_se3 << " m";
  const Run mono_off = run(false, true), mono_on = run(true, true);
  EXPECT_EQ(mono_off.followed, 0u);
  EXPECT_GT(mono_on.followed, 100u);
  EXPECT_GT(mono_on.observations_per_point, mono_off.observations_per_point);
  RecordProperty("mono_observations_per_point_off", std::to_string(mono_off.observations_per_point));
  RecordProperty("mono_observations_per_point_on", std::to_string(mono_on.observations_per_point));
}

// The flow under its time budget (tracking.flow_budget_ms_mono): a threaded run whose frames take
// longer than the budget runs the flow for its first window of tracked frames only, then stops; a
// --deterministic one (no mapper thread) ignores the budget and runs it on every frame.
TEST(FrontProcess, FlowStopsOverItsTimeBudgetInThreadedRunsOnly) {
  const fs::path bin = wardmap_binary();
  if (!fs::exists(bin)) GTEST_SKIP() << "wardmap executable not built: " << bin;
  const fs::path seq = test::scratch_dir() / "aisle_budget";
  ASSERT_TRUE(render(seq, "--scenario aisle_straight --variant quick --seed 2 --frames 60"));
  const io::Settings settings = io::load_settings(seq / "settings.yaml");
  auto reader = io::open_sequence(seq);
  const auto run = [&](bool threaded, double budget_ms) {
    FrontOptions options = load_front_options(settings);
    options.monocular = true;
    options.mapping_thread = threaded;
    options.tracking.flow_extend_mono = true;
    options.tracking.flow_budget_ms_mono = budget_ms;
    options.tracking.flow_budget_frames = 10;
    options.tracking.flow_budget_retry = 1000;
    FrontProcess front(options, settings.camera.camera);
    std::vector<FrameResult> results;
    for (size_t i = 0; i < reader->size(); ++i) results.push_back(front.process(reader->read(i)));
    front.finish();
    return results;
  };
  const auto flow_frames = [](const std::vector<FrameResult>& rs) {
    return std::count_if(rs.begin(), rs.end(), [](const FrameResult& r) { return r.flow; });
  };
  // 1 microsecond: every frame is over it.
  const std::vector<FrameResult> threaded = run(true, 1e-3);
  const auto first_tracked = std::find_if(threaded.begin(), threaded.end(), [](const FrameResult& r) {
    return r.tracked && r.state == TrackingState::kTracking;
  });
  ASSERT_LT(first_tracked + 20, threaded.end()) << "the monocular map was not made in time";
  // On until the first window of 10 tracked frames is weighed, then off for good (retry 1000).
  for (auto r = threaded.begin(); r != threaded.end(); ++r) {
    const bool in_first_window = r <= first_tracked + 9;
    EXPECT_EQ(r->flow, in_first_window) << "frame " << (r - threaded.begin());
  }
  const std::vector<FrameResult> deterministic = run(false, 1e-3);
  EXPECT_EQ(flow_frames(deterministic), static_cast<long>(deterministic.size()));
  const std::vector<FrameResult> no_budget = run(true, 0.0);
  EXPECT_EQ(flow_frames(no_budget), static_cast<long>(no_budget.size()));
  // The budget is given for 640 x 480 and scales with the pixels: KITTI's 1241 x 376 gets 1.52 times it.
  TrackingOptions t;
  PinholeCamera vga, kitti;
  vga.width = 640;
  vga.height = 480;
  kitti.width = 1241;
  kitti.height = 376;
  EXPECT_DOUBLE_EQ(flow_budget_seconds(t, true, vga), 0.010);
  EXPECT_NEAR(flow_budget_seconds(t, true, kitti), 0.010 * 1241 * 376 / (640.0 * 480.0), 1e-12);
  EXPECT_DOUBLE_EQ(flow_budget_seconds(t, false, vga), 0.015);
}

// A monocular camera standing still cannot initialise (no parallax). With tracking.init_still_px the
// reference frame is kept past tracking.init_max_frames while every frame shows its view unmoved, and
// once the camera moves and the map exists, the still frames take the first keyframe's pose. ORB-SLAM's
// rule (0) replaces the reference and loses all but the last window of still frames.
TEST(FrontProcess, MonocularStillStartIsLocalisedOnceTheCameraMoves) {
  const fs::path bin = wardmap_binary();
  if (!fs::exists(bin)) GTEST_SKIP() << "wardmap executable not built: " << bin;
  const fs::path seq = test::scratch_dir() / "aisle_still";
  ASSERT_TRUE(render(seq, "--scenario aisle_straight --variant slow --seed 1 --frames 60"));
  const io::Settings settings = io::load_settings(seq / "settings.yaml");
  auto reader = io::open_sequence(seq);
  const Trajectory& gt = reader->ground_truth();
  ASSERT_EQ(gt.size(), 60u);
  // The first frame, shown still_frames times, then the others; frames renumbered at 30 Hz.
  const int still_frames = 75;  // two and a half initialisation windows (tracking.init_max_frames 30)
  const size_t count = static_cast<size_t>(still_frames) + reader->size() - 1;
  const auto source_of = [&](size_t k) {
    return k < static_cast<size_t>(still_frames) ? size_t{0} : k - static_cast<size_t>(still_frames) + 1;
  };
  Trajectory truth;
  for (size_t k = 0; k < count; ++k) truth.push_back(static_cast<double>(k) / 30, gt.poses[source_of(k)]);
  const auto run = [&](double still_px) {
    FrontOptions options = load_front_options(settings);
    options.monocular = true;
    options.tracking.init_still_px = still_px;
    FrontProcess front(options, settings.camera.camera);
    for (size_t k = 0; k < count; ++k) {
      io::Frame f = reader->read(source_of(k));
      f.index = k;
      f.timestamp = truth.timestamps[k];
      front.process(f);
    }
    return front.trajectory();
  };
  const Trajectory est = run(1.0);
  ASSERT_EQ(est.size(), truth.size()) << "every frame localised";
  // The still frames stay at the first one's place (to 1 % of the path, the map's scale being arbitrary).
  const double path = (est.poses.back().translation() - est.poses[0].translation()).norm();
  for (int k = 1; k < still_frames; ++k)
    EXPECT_LT((est.poses[static_cast<size_t>(k)].translation() - est.poses[0].translation()).norm(), 0.01 * path)
        << "still frame " << k;
  const auto pairs = eval::associate(truth, est, eval::AssociationOptions{});
  const double ate = eval::compute_ate(truth, est, pairs, eval::Alignment::Sim3).stats.rmse;
  EXPECT_LE(ate, 0.02) << "ATE (Sim(3)) RMSE " << ate << " m";
  RecordProperty("ate_sim3_m", std::to_string(ate));

  const Trajectory old_rule = run(0.0);
  EXPECT_LE(old_rule.size(), truth.size() - static_cast<size_t>(still_frames - 31))
      << "the old rule keeps at most the last window of still frames";
  RecordProperty("localised_old_rule", std::to_string(old_rule.size()) + " of " + std::to_string(truth.size()));
}

// A stop in the middle of a run (tracking.keyframe_still_px): while the camera stands still, no
// keyframe is made (at most one, for the motion since the last keyframe before the stop); with 0,
// one every tracking.keyframe_max_frames, as before. Every frame stays tracked either way.
TEST(FrontProcess, RgbdCameraStandingStillMakesNoKeyframes) {
  const fs::path bin = wardmap_binary();
  if (!fs::exists(bin)) GTEST_SKIP() << "wardmap executable not built: " << bin;
  const fs::path seq = test::scratch_dir() / "aisle_stop";
  ASSERT_TRUE(render(seq, "--scenario aisle_straight --variant slow --seed 1 --frames 60"));
  const io::Settings settings = io::load_settings(seq / "settings.yaml");
  auto reader = open_with_depth(seq, settings);
  const Trajectory& gt = reader->ground_truth();
  ASSERT_EQ(gt.size(), 60u);
  // Frame 30 shown still_frames times; frames renumbered at 30 Hz.
  const size_t stop = 30, still_frames = 60;
  const size_t count = reader->size() + still_frames - 1;
  const auto source_of = [&](size_t k) { return k < stop ? k : k < stop + still_frames ? stop : k - still_frames + 1; };
  Trajectory truth;
  for (size_t k = 0; k < count; ++k) truth.push_back(static_cast<double>(k) / 30, gt.poses[source_of(k)]);
  struct Outcome {
    int tracked = 0, still_keyframes = 0;
    Trajectory trajectory;
  };
  const auto run = [&](double still_px) {
    FrontOptions options = load_front_options(settings);
    options.tracking.keyframe_still_px = still_px;
    FrontProcess front(options, settings.camera.camera);
    Outcome o;
    for (size_t k = 0; k < count; ++k) {
      io::Frame f = reader->read(source_of(k));
      f.index = k;
      f.timestamp = truth.timestamps[k];
      const FrameResult r = front.process(f);
      o.tracked += r.tracked ? 1 : 0;
      if (k > stop && k < stop + still_frames && r.keyframe) ++o.still_keyframes;
    }
    o.trajectory = front.trajectory();
    return o;
  };
  const Outcome still = run(1.0);
  EXPECT_EQ(still.tracked, static_cast<int>(count));
  EXPECT_LE(still.still_keyframes, 1);
  const auto pairs = eval::associate(truth, still.trajectory, eval::AssociationOptions{});
  const double ate = eval::compute_ate(truth, still.trajectory, pairs, eval::Alignment::SE3).stats.rmse;
  EXPECT_LE(ate, 0.02) << "ATE RMSE " << ate << " m";
  RecordProperty("ate_rmse_m", std::to_string(ate));

  const Outcome off = run(0.0);
  EXPECT_EQ(off.tracked, static_cast<int>(count));
  EXPECT_GE(off.still_keyframes, 4) << "keyframe_max_frames (10) over " << still_frames << " still frames";
  RecordProperty("still_keyframes_rule_off", std::to_string(off.still_keyframes));
}

}  // namespace wardmap::slam
