#include "semantics/keyframe_groups.h"

#include <gtest/gtest.h>

namespace wardmap::semantics {
namespace {

TEST(KeyframeGrouper, GroupsOfMWithJOverlap) {
  GroupOptions o;
  o.size = 4;
  o.overlap = 1;
  KeyframeGrouper g(o);
  std::vector<int> completed;
  for (int k = 0; k < 11; ++k)
    for (int n : g.add_keyframe(k)) completed.push_back(n);
  ASSERT_EQ(completed, (std::vector<int>{0, 1, 2}));
  EXPECT_EQ(g.group(0), (std::vector<int>{0, 1, 2, 3}));
  EXPECT_EQ(g.group(1), (std::vector<int>{3, 4, 5, 6}));
  EXPECT_EQ(g.group(2), (std::vector<int>{6, 7, 8, 9}));
  EXPECT_EQ(g.flush(), 3);  // keyframe 10 is in no complete group
  EXPECT_EQ(g.group(3), (std::vector<int>{9, 10}));
  EXPECT_EQ(g.flush(), -1);
}

TEST(KeyframeGrouper, FlushWithNothingNewAddsNoGroup) {
  GroupOptions o;
  o.size = 3;
  o.overlap = 1;
  KeyframeGrouper g(o);
  for (int k = 0; k < 5; ++k) g.add_keyframe(k);  // groups {0,1,2}, {2,3,4}
  EXPECT_EQ(g.num_groups(), 2);
  EXPECT_EQ(g.flush(), -1);
}

TEST(KeyframeSelector, MotionOrIntervalMakesAKeyframe) {
  KeyframeSelectionOptions o;
  o.min_translation = 0.1;
  o.min_rotation_deg = 5;
  o.max_interval = 5;
  KeyframeSelector s(o);
  EXPECT_TRUE(s.accept(slam::SE3()));
  EXPECT_FALSE(s.accept(slam::SE3(Eigen::Quaterniond::Identity(), Eigen::Vector3d(0.05, 0, 0))));
  EXPECT_TRUE(s.accept(slam::SE3(Eigen::Quaterniond::Identity(), Eigen::Vector3d(0.11, 0, 0))));
  const slam::SE3 turned(Eigen::Quaterniond(Eigen::AngleAxisd(0.1, Eigen::Vector3d::UnitY())), Eigen::Vector3d(0.11, 0, 0));
  EXPECT_TRUE(s.accept(turned));  // 5.7 degrees
  for (int i = 0; i < 4; ++i) EXPECT_FALSE(s.accept(turned));
  EXPECT_TRUE(s.accept(turned));  // fifth frame since the last keyframe
}

}  // namespace
}  // namespace wardmap::semantics
