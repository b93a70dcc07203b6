#include "semantics/keyframe_groups.h"

#include <gtest/gtest.h>

#include "tests/semantics/core/options_error.h"

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
  const slam::SE3 crept(turned.rotation(), Eigen::Vector3d(0.13, 0, 0));  // 2 cm on: not standing still
  for (int i = 0; i < 4; ++i) EXPECT_FALSE(s.accept(crept));
  EXPECT_TRUE(s.accept(crept));  // fifth frame since the last keyframe
}

// A camera standing still (a robot waiting at a lift) makes no keyframe from the interval rule:
// each would detect the same view again. Creeping on, it makes one once it has moved
// still_translation since the last keyframe; 0 and 0 turn the rule off.
TEST(KeyframeSelector, StandingStillMakesNoIntervalKeyframe) {
  KeyframeSelectionOptions o;
  o.max_interval = 5;  // still_translation 0.01 m, still_rotation_deg 0.5
  const auto at = [](double x, double yaw_deg) {
    return slam::SE3(Eigen::Quaterniond(Eigen::AngleAxisd(yaw_deg * M_PI / 180, Eigen::Vector3d::UnitY())),
                     Eigen::Vector3d(x, 0, 0));
  };
  KeyframeSelector s(o);
  EXPECT_TRUE(s.accept(at(0, 0)));
  for (int i = 0; i < 20; ++i) EXPECT_FALSE(s.accept(at(0.002, 0.1))) << "frame " << i + 1;
  EXPECT_TRUE(s.accept(at(0.012, 0.1)));  // 1.2 cm from the last keyframe, 20 frames on
  for (int i = 0; i < 4; ++i) EXPECT_FALSE(s.accept(at(0.012, 0.1)));
  EXPECT_FALSE(s.accept(at(0.012, 0.1)));  // the fifth frame, still
  EXPECT_TRUE(s.accept(at(0.012, 0.7)));   // turned 0.6 degrees: no longer still

  o.still_translation = 0;
  o.still_rotation_deg = 0;
  KeyframeSelector off(o);
  EXPECT_TRUE(off.accept(at(0, 0)));
  for (int i = 0; i < 4; ++i) EXPECT_FALSE(off.accept(at(0, 0)));
  EXPECT_TRUE(off.accept(at(0, 0)));  // the fifth frame, as before the rule
}

TEST(KeyframeSelector, InvalidStillLimitsNameTheKey) {
  test::expect_load_error_names("keyframes: {still_translation: -0.01}", "semantics.keyframes.still_translation");
  test::expect_load_error_names("keyframes: {still_rotation_deg: 200}", "semantics.keyframes.still_rotation_deg");
}

}  // namespace
}  // namespace wardmap::semantics
