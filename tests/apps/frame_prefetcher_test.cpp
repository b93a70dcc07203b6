// The run's frame prefetcher (apps/frame_prefetcher.h): frames in order and as a direct read gives
// them, a read error thrown at the frame it concerns, and no hang when the run stops early.
#include <gtest/gtest.h>

#include <stdexcept>

#include "apps/frame_prefetcher.h"
#include "slam/core/errors.h"
#include "tests/slam/io/fixtures.h"
#include "tests/support/test_support.h"

namespace wardmap::apps {
namespace {

namespace fs = std::filesystem;

// ahead = 0 reads on the caller's thread, 1 and 2 on the prefetcher's.
class FramePrefetcherAhead : public ::testing::TestWithParam<size_t> {};

TEST_P(FramePrefetcherAhead, GivesEveryFrameInOrderAsReadGivesIt) {
  const fs::path root = test::scratch_dir();
  test::make_tum(root);
  auto reader = slam::io::open_sequence(root);
  auto direct = slam::io::open_sequence(root);
  FramePrefetcher frames(*reader, GetParam());
  for (size_t i = 0; i < reader->size(); ++i) {
    const slam::io::Frame f = frames.next(), g = direct->read(i);
    EXPECT_EQ(f.index, i);
    EXPECT_DOUBLE_EQ(f.timestamp, g.timestamp);
    EXPECT_EQ(cv::norm(f.image, g.image, cv::NORM_INF), 0.0);
    EXPECT_EQ(cv::norm(f.depth, g.depth, cv::NORM_INF), 0.0);
    ASSERT_TRUE(f.gt_pose.has_value());
    EXPECT_TRUE(f.gt_pose->translation().isApprox(g.gt_pose->translation()));
  }
  EXPECT_THROW(frames.next(), std::out_of_range);
}

TEST_P(FramePrefetcherAhead, ThrowsTheReadErrorAtItsFrame) {
  const fs::path root = test::scratch_dir();
  test::make_kitti(root);
  auto reader = slam::io::open_sequence(root);
  const fs::path broken = root / "sequences" / "05" / "image_0" / "000001.png";
  test::write_text(broken, "not a png");  // after opening: the decode fails
  FramePrefetcher frames(*reader, GetParam());
  EXPECT_EQ(frames.next().image.at<uchar>(0, 0), 20);
  try {
    frames.next();
    FAIL() << "the broken frame was returned";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("000001.png"), std::string::npos) << e.what();
  }
  EXPECT_THROW(frames.next(), InputError);  // again, rather than a later frame or a hang
}

INSTANTIATE_TEST_SUITE_P(InlineAndThreaded, FramePrefetcherAhead, ::testing::Values(0, 1, 2));

TEST(FramePrefetcher, StopsWhenLeftEarly) {
  const fs::path root = test::scratch_dir();
  test::make_tum(root);
  auto reader = slam::io::open_sequence(root);
  {
    FramePrefetcher frames(*reader, 1);  // the thread waits for room after one frame
    EXPECT_EQ(frames.next().index, 0u);
  }  // destroyed with frames still to read: must not hang
  FramePrefetcher again(*reader);
  EXPECT_EQ(again.next().index, 0u);
}

}  // namespace
}  // namespace wardmap::apps
