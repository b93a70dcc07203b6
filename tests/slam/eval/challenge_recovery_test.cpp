#include "slam/eval/challenge_recovery.h"

#include <gtest/gtest.h>

#include <fstream>

#include "slam/core/errors.h"
#include "tests/support/test_support.h"

namespace wardmap::slam::eval {
namespace {

// Frames at 10 Hz from t = 0; status and submap given per frame.
std::vector<FrameState> frames_of(const std::string& statuses, const std::vector<int>& submaps) {
  std::vector<FrameState> f;
  for (size_t i = 0; i < statuses.size(); ++i) {
    const char c = statuses[i];
    f.push_back({0.1 * static_cast<double>(i),
                 c == 'T'   ? "tracked"
                 : c == 'R' ? "relocalised"
                 : c == 'B' ? "backfilled"
                 : c == 'I' ? "initialising"
                            : "lost",
                 submaps[i]});
  }
  return f;
}

TEST(ChallengeRecovery, LostInsideThenResumedInANewSubmap) {
  // frames 0-3 tracked in submap 0; lost 4-6; initialising 7-8 in submap 1; tracked from 9.
  const auto frames = frames_of("TTTTLLLIITTT", {0, 0, 0, 0, 0, 0, 0, 1, 1, 1, 1, 1});
  const auto r = challenge_recovery(frames, {{0.35, 0.75, "dark"}});
  ASSERT_EQ(r.size(), 1u);
  EXPECT_TRUE(r[0].covered);
  EXPECT_EQ(r[0].frames_inside, 4);  // 0.4 ... 0.7
  EXPECT_EQ(r[0].lost_inside, 4);
  EXPECT_EQ(r[0].submap_before, 0);
  ASSERT_TRUE(r[0].resumed_after);
  EXPECT_NEAR(*r[0].resumed_after, 0.9 - 0.75, 1e-9);  // frame 9
  EXPECT_EQ(r[0].submap_after, 1);
  EXPECT_TRUE(r[0].new_submap());
}

TEST(ChallengeRecovery, BackfilledAndRelocalisedFramesCountAsLocalised) {
  // Relocalised in the same submap right at the segment's end: no new submap, resumed at once.
  auto r = challenge_recovery(frames_of("TTLLRT", {0, 0, 0, 0, 0, 0}), {{0.15, 0.4, "blur"}});
  ASSERT_EQ(r.size(), 1u);
  ASSERT_TRUE(r[0].resumed_after);
  EXPECT_NEAR(*r[0].resumed_after, 0.0, 1e-9);
  EXPECT_FALSE(r[0].new_submap());
  // A monocular initialisation localises frames after the fact: they are "backfilled".
  r = challenge_recovery(frames_of("TLLBBT", {0, 0, 0, 1, 1, 1}), {{0.05, 0.25, "dark"}});
  ASSERT_TRUE(r[0].resumed_after);
  EXPECT_NEAR(*r[0].resumed_after, 0.3 - 0.25, 1e-9);
  EXPECT_TRUE(r[0].new_submap());
}

TEST(ChallengeRecovery, NeverResumedOrNotReachedOrOutsideTheRun) {
  const auto frames = frames_of("TTTLLL", {0, 0, 0, 0, 0, 0});
  const auto r = challenge_recovery(frames, {{0.25, 0.35, "textureless"},  // lost, never back
                                             {0.45, 0.9, "fast-turn"},     // past the last frame
                                             {2.0, 3.0, "blur"}});         // outside the run: left out
  ASSERT_EQ(r.size(), 2u);
  EXPECT_TRUE(r[0].covered);
  EXPECT_FALSE(r[0].resumed_after);
  EXPECT_FALSE(r[0].new_submap());
  EXPECT_EQ(r[0].lost_inside, 1);
  EXPECT_FALSE(r[1].covered);
  EXPECT_FALSE(r[1].resumed_after);
  EXPECT_TRUE(challenge_recovery({}, {{0, 1, "dark"}}).empty());
}

TEST(ChallengeRecovery, TrackedThroughASegment) {
  // Frames 1-3 inside; the first frame at or after the end is frame 4, 0.05 s after it.
  const auto r = challenge_recovery(frames_of("TTTTT", {0, 0, 0, 0, 0}), {{0.05, 0.35, "blur"}});
  ASSERT_EQ(r.size(), 1u);
  EXPECT_EQ(r[0].frames_inside, 3);
  EXPECT_EQ(r[0].lost_inside, 0);
  ASSERT_TRUE(r[0].resumed_after);
  EXPECT_NEAR(*r[0].resumed_after, 0.05, 1e-9);
  EXPECT_FALSE(r[0].new_submap());
}

TEST(ChallengeRecovery, HeldCountsOnlyTrackingThatLasts) {
  // Segment 0.05-0.25. Frame 3 is localised in a new submap that is lost at once (frames 4-5); a
  // second submap holds from frame 6.
  const auto frames = frames_of("TLLTLLTTTTTT", {0, 0, 0, 1, 1, 1, 2, 2, 2, 2, 2, 2});
  auto r = challenge_recovery(frames, {{0.05, 0.25, "fast-turn"}}, /*hold_frames=*/4);
  ASSERT_EQ(r.size(), 1u);
  ASSERT_TRUE(r[0].resumed_after);
  EXPECT_NEAR(*r[0].resumed_after, 0.3 - 0.25, 1e-9);  // frame 3
  EXPECT_EQ(r[0].submap_after, 1);
  ASSERT_TRUE(r[0].held_after);
  EXPECT_NEAR(*r[0].held_after, 0.6 - 0.25, 1e-9);  // frame 6: frames 6-9 localised
  // Fewer frames left than hold_frames: all of them localised is enough.
  r = challenge_recovery(frames, {{0.05, 0.25, "fast-turn"}}, /*hold_frames=*/10);
  ASSERT_TRUE(r[0].held_after);
  EXPECT_NEAR(*r[0].held_after, 0.6 - 0.25, 1e-9);
  // Lost again at the very end: never held.
  r = challenge_recovery(frames_of("TLLTTTL", {0, 0, 0, 1, 1, 1, 1}), {{0.05, 0.25, "blur"}}, 3);
  ASSERT_TRUE(r[0].resumed_after);
  EXPECT_NEAR(*r[0].held_after, 0.05, 1e-9);  // frames 3-5
  r = challenge_recovery(frames_of("TLLTTL", {0, 0, 0, 1, 1, 1}), {{0.05, 0.25, "blur"}}, 3);
  EXPECT_TRUE(r[0].resumed_after);
  EXPECT_FALSE(r[0].held_after);
}

void write(const std::filesystem::path& file, const std::string& text) { std::ofstream(file) << text; }

TEST(ReadChallenges, ReadsTheSynthWritersFormat) {
  const auto dir = test::scratch_dir();
  write(dir / "challenges.txt", "# t_begin t_end kind\n1001.466667 1002.933333 dark\n1005.5 1006.25 fast-turn\n");
  const auto c = read_challenges(dir / "challenges.txt");
  ASSERT_EQ(c.size(), 2u);
  EXPECT_DOUBLE_EQ(c[0].begin, 1001.466667);
  EXPECT_DOUBLE_EQ(c[0].end, 1002.933333);
  EXPECT_EQ(c[0].kind, "dark");
  EXPECT_EQ(c[1].kind, "fast-turn");
  // The kind is only reported: a kind of a later synth is read, not refused.
  write(dir / "challenges.txt", "1 2 fog\n");
  EXPECT_EQ(read_challenges(dir / "challenges.txt").at(0).kind, "fog");
}

TEST(ReadChallenges, BadLinesNameTheFileAndLine) {
  const auto dir = test::scratch_dir();
  const auto expect_error = [&](const std::string& text, const std::string& what) {
    write(dir / "challenges.txt", text);
    try {
      read_challenges(dir / "challenges.txt");
      ADD_FAILURE() << "no error for: " << text;
    } catch (const InputError& e) {
      const std::string m = e.what();
      EXPECT_NE(m.find("challenges.txt:2"), std::string::npos) << m;
      EXPECT_NE(m.find(what), std::string::npos) << m;
    }
  };
  expect_error("1 2 dark\n3 4\n", "expected 't_begin t_end kind'");
  expect_error("1 2 dark\n3 x dark\n", "t_end: 'x' is not a number");
  expect_error("1 2 dark\n4 3 dark\n", "is before t_begin");
  expect_error("1 2 dark\n3 inf dark\n", "t_end: 'inf' is not a number");
  EXPECT_THROW(read_challenges(dir / "absent.txt"), InputError);
}

}  // namespace
}  // namespace wardmap::slam::eval
