#include "mot/mot_metrics.h"

#include <gtest/gtest.h>

namespace wardmap::mot {
namespace {

TEST(ClearMot, CountsIdSwitchesOnHandMadeCase) {
  // gt 1 keeps hyp 10, is missed, comes back as 10 (no switch); gt 2 is hyp 20, then 21 (switch), then
  // back to 20 (switch again); gt 3 appears late as 30, swaps with gt 1's hypothesis (two switches).
  std::vector<FrameCorrespondences> frames(5);
  frames[0].matches = {{1, 10}, {2, 20}};
  frames[1].matches = {{2, 21}};
  frames[1].misses = 1;
  frames[2].matches = {{1, 10}, {2, 20}, {3, 30}};
  frames[2].false_positives = 2;
  frames[3].matches = {{1, 30}, {3, 10}, {2, 20}};
  frames[4].matches = {{1, 30}, {3, 10}};
  frames[4].misses = 1;
  const ClearMotResult r = clear_mot(frames);
  EXPECT_EQ(r.frames, 5);
  EXPECT_EQ(r.matches, 11);
  EXPECT_EQ(r.misses, 2);
  EXPECT_EQ(r.false_positives, 2);
  EXPECT_EQ(r.ground_truth, 13);
  EXPECT_EQ(r.id_switches, 4);
  EXPECT_NEAR(r.mota, 1.0 - (2.0 + 2.0 + 4.0) / 13.0, 1e-12);
}

TEST(ClearMot, PerfectTrackingHasMotaOne) {
  ClearMotAccumulator acc;
  for (int f = 0; f < 10; ++f) acc.add_frame({{{1, 5}, {2, 6}}, 0, 0});
  EXPECT_EQ(acc.result().id_switches, 0);
  EXPECT_DOUBLE_EQ(acc.result().mota, 1.0);
}

}  // namespace
}  // namespace wardmap::mot
