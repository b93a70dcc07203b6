#include "slam/front/flow_budget.h"

#include <gtest/gtest.h>

#include <vector>

namespace wardmap::slam {
namespace {

// Records n frames of the same time; returns whether the flow was active before each of them.
std::vector<bool> feed(FlowBudget& b, int n, double seconds) {
  std::vector<bool> active;
  for (int i = 0; i < n; ++i) {
    active.push_back(b.active());
    b.record(seconds);
  }
  return active;
}

TEST(FlowBudget, NoBudgetKeepsTheFlowOn) {
  FlowBudget b(0.0, 5, 3);
  feed(b, 100, 1.0);
  EXPECT_TRUE(b.active());
  EXPECT_EQ(b.windows_on(), 0);  // nothing measured: no decision to take
}

// The decision holds for whole windows (skipping the flow on single frames breaks its chains), and
// a window's median, not one slow frame, decides.
TEST(FlowBudget, DecidesOncePerWindowOnItsMedian) {
  FlowBudget b(0.010, 5, 3);
  for (double t : {0.005, 0.100, 0.006, 0.090, 0.007}) {  // median 7 ms: two slow frames only
    EXPECT_TRUE(b.active());
    b.record(t);
  }
  EXPECT_TRUE(b.active());
  const std::vector<bool> before = feed(b, 5, 0.012);
  EXPECT_EQ(before, std::vector<bool>(5, true)) << "switched off inside a window";
  EXPECT_FALSE(b.active());
  EXPECT_EQ(b.windows_on(), 2);
  EXPECT_EQ(b.windows_off(), 0);
}

// Off, it comes back when the frame time plus the flow's measured cost (last on-window's median less
// the first off-window's) fits the budget.
TEST(FlowBudget, BackOnWhenTheMeasuredCostFits) {
  FlowBudget b(0.010, 4, 100);
  feed(b, 4, 0.012);  // on: 12 ms, over
  ASSERT_FALSE(b.active());
  feed(b, 4, 0.008);  // off: 8 ms, so the flow costs 4 ms; 8 + 4 > 10
  EXPECT_FALSE(b.active());
  feed(b, 4, 0.0065);  // 6.5 + 4 > 10
  EXPECT_FALSE(b.active());
  feed(b, 4, 0.0055);  // 5.5 + 4 <= 10: the host got faster
  EXPECT_TRUE(b.active());
  EXPECT_EQ(b.windows_on(), 1);
  EXPECT_EQ(b.windows_off(), 3);
  feed(b, 4, 0.0095);  // on, within the budget: stays on
  EXPECT_TRUE(b.active());
}

// Its cost is measured again after `retry` off-windows in a row, whatever the estimate says.
TEST(FlowBudget, MeasuresItsCostAgainAfterRetryWindows) {
  FlowBudget b(0.010, 4, 3);
  feed(b, 4, 0.020);  // on: 20 ms
  feed(b, 4, 0.008);  // off: cost 12 ms
  feed(b, 4, 0.008);
  EXPECT_FALSE(b.active());
  feed(b, 4, 0.008);  // third off-window: try again
  EXPECT_TRUE(b.active());
  feed(b, 4, 0.009);  // now it fits: the host's load fell
  EXPECT_TRUE(b.active());
  feed(b, 4, 0.011);
  EXPECT_FALSE(b.active());
  feed(b, 4, 0.008);  // the cost measured anew: 3 ms; 8 + 3 > 10
  EXPECT_FALSE(b.active());
  feed(b, 4, 0.007);  // 7 + 3 <= 10
  EXPECT_TRUE(b.active());
}

// A retry over the budget doubles the wait for the next one; a window within the budget resets it.
TEST(FlowBudget, FailedRetriesBackOff) {
  FlowBudget b(0.010, 2, 2);
  const auto windows_until_on = [&b] {
    int n = 0;
    while (!b.active() && n < 100) {
      feed(b, 2, 0.008);  // off: 8 ms; the flow's cost (12 ms) never fits
      ++n;
    }
    return n;
  };
  feed(b, 2, 0.020);  // the first window: over
  feed(b, 2, 0.008);  // cost 12 ms
  EXPECT_EQ(windows_until_on(), 1);  // the second off-window: retry (2)
  feed(b, 2, 0.020);  // failed
  EXPECT_EQ(windows_until_on(), 4);
  feed(b, 2, 0.020);  // failed again
  EXPECT_EQ(windows_until_on(), 8);
  feed(b, 2, 0.009);  // within the budget: stays on, and the wait is back to 2
  ASSERT_TRUE(b.active());
  feed(b, 2, 0.020);
  EXPECT_EQ(windows_until_on(), 2);
}

// A new submap gets the flow for its first window, whatever the budget decided for the old one; the
// window then decides as usual, and the measured cost is kept.
TEST(FlowBudget, RestartGivesANewMapItsFirstWindow) {
  FlowBudget b(0.010, 4, 100);
  feed(b, 4, 0.012);  // over: off
  feed(b, 2, 0.008);  // half an off-window
  ASSERT_FALSE(b.active());
  b.restart();
  EXPECT_TRUE(b.active());
  const std::vector<bool> before = feed(b, 4, 0.012);  // a whole window on, the half window dropped
  EXPECT_EQ(before, std::vector<bool>(4, true));
  EXPECT_FALSE(b.active());
  EXPECT_EQ(b.windows_on(), 2);
  EXPECT_EQ(b.windows_off(), 0);
  b.restart();
  feed(b, 4, 0.009);  // within the budget: stays on
  EXPECT_TRUE(b.active());
  FlowBudget none(0.0, 4, 100);  // no budget: restart changes nothing
  none.restart();
  EXPECT_TRUE(none.active());
}

}  // namespace
}  // namespace wardmap::slam
