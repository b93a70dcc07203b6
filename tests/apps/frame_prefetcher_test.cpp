// The run's frame prefetcher (apps/frame_prefetcher.h): frames in order and as a direct read gives
// them, a read error thrown at the frame it concerns (the frames after it still given), and no hang
// when the run stops early.
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
  } catch (const FrameReadError& e) {
    EXPECT_NE(std::string(e.what()).find("000001.png"), std::string::npos) << e.what();
    EXPECT_EQ(e.frame(), 1u);
  }
  // That frame only: the run goes on with the next ones, in order, and then ends.
  for (size_t i = 2; i < reader->size(); ++i) EXPECT_EQ(frames.next().index, i);
  EXPECT_THROW(frames.next(), std::out_of_range);
}

TEST_P(FramePrefetcherAhead, SkipsUnreadableFramesOneAfterAnotherUpToTheEnd) {
  const fs::path root = test::scratch_dir();
  test::make_kitti(root);
  auto reader = slam::io::open_sequence(root);
  ASSERT_EQ(reader->size(), 3u);
  for (const char* name : {"000001.png", "000002.png"})
    test::write_text(root / "sequences" / "05" / "image_0" / name, "cut short");
  FramePrefetcher frames(*reader, GetParam());
  EXPECT_EQ(frames.next().index, 0u);
  for (size_t i = 1; i <= 2; ++i) {
    try {
      frames.next();
      FAIL() << "frame " << i << " was returned";
    } catch (const FrameReadError& e) {
      EXPECT_EQ(e.frame(), i);
    }
  }
  EXPECT_THROW(frames.next(), std::out_of_range);
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
