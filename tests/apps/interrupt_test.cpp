// The first SIGINT / SIGTERM inside an InterruptScope is a request the run loop reads; a second one
// ends the process as the default action does; outside a scope the default action is back.
#include "apps/interrupt.h"

#include <gtest/gtest.h>

#include <csignal>
#include <cstdlib>

namespace wardmap::apps {
namespace {

TEST(InterruptScope, FirstSignalIsARequest) {
  {
    InterruptScope scope;
    EXPECT_EQ(InterruptScope::requested(), 0);
    std::raise(SIGTERM);
    EXPECT_EQ(InterruptScope::requested(), SIGTERM);
  }
  InterruptScope again;  // a new scope starts with no request
  EXPECT_EQ(InterruptScope::requested(), 0);
  std::raise(SIGINT);
  EXPECT_EQ(InterruptScope::requested(), SIGINT);
  EXPECT_EQ(signal_name(SIGINT), "SIGINT");
  EXPECT_EQ(signal_name(SIGTERM), "SIGTERM");
}

TEST(InterruptScopeDeathTest, SecondSignalEndsTheProcess) {
  GTEST_FLAG_SET(death_test_style, "threadsafe");
  EXPECT_EXIT(
      {
        InterruptScope scope;
        std::raise(SIGINT);
        if (InterruptScope::requested() != SIGINT) std::exit(3);
        std::raise(SIGINT);
        std::exit(4);  // not reached
      },
      testing::KilledBySignal(SIGINT), "");
}

TEST(InterruptScopeDeathTest, DefaultActionOutsideAScope) {
  GTEST_FLAG_SET(death_test_style, "threadsafe");
  EXPECT_EXIT(
      {
        { InterruptScope scope; }
        std::raise(SIGTERM);
        std::exit(4);  // not reached
      },
      testing::KilledBySignal(SIGTERM), "");
}

}  // namespace
}  // namespace wardmap::apps
