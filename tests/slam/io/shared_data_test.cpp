// The shared real sequences open as the issue states (skipped when ../shared is absent).
#include <gtest/gtest.h>

#include "slam/io/sequence.h"
#include "tests/support/test_support.h"

namespace wardmap::slam::io {
namespace {

TEST(SharedData, Kitti03) {
  WARDMAP_REQUIRE_DATA("kitti-odometry-03");
  auto r = open_sequence(test::shared_data_dir() / "kitti-odometry-03");
  EXPECT_EQ(r->info().kind, DatasetKind::Kitti);
  EXPECT_EQ(r->size(), 400u);
  EXPECT_EQ(r->info().width, 1242);
  EXPECT_EQ(r->info().height, 375);
  EXPECT_DOUBLE_EQ(r->info().fps, 10.0);
  EXPECT_EQ(r->info().frames_with_ground_truth, 400u);
  const Frame last = r->read(399);
  EXPECT_EQ(last.image.channels(), 1);
  EXPECT_NEAR(last.timestamp, 41.28276, 1e-5);
}

TEST(SharedData, SevenScenesRedKitchen) {
  WARDMAP_REQUIRE_DATA("7scenes-redkitchen");
  auto r = open_sequence(test::shared_data_dir() / "7scenes-redkitchen");
  EXPECT_EQ(r->info().kind, DatasetKind::SevenScenes);
  EXPECT_EQ(r->size(), 600u);
  EXPECT_TRUE(r->info().has_depth);
  EXPECT_EQ(r->info().frames_with_ground_truth, 600u);
  const Frame f = r->read(100);
  EXPECT_EQ(f.depth.type(), CV_32F);
  double lo, hi;
  cv::minMaxLoc(f.depth, &lo, &hi, nullptr, nullptr, f.depth > 0);
  EXPECT_GT(lo, 0.2);  // a kitchen seen from 0.5-4 m
  EXPECT_LT(hi, 8.0);
}

}  // namespace
}  // namespace wardmap::slam::io
