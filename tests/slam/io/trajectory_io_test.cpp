#include "slam/io/trajectory_io.h"

#include <gtest/gtest.h>

#include "slam/core/errors.h"
#include "tests/slam/io/fixtures.h"
#include "tests/support/test_support.h"

namespace wardmap::slam::io {
namespace {

Trajectory sample() {
  Trajectory t;
  for (int i = 0; i < 5; ++i)
    t.push_back(100.0 + i / 30.0, SE3(Eigen::Quaterniond(Eigen::AngleAxisd(0.1 * i, Eigen::Vector3d(0, 1, 1).normalized())),
                                      Eigen::Vector3d(i, -0.5 * i, 2)));
  return t;
}

TEST(TrajectoryIo, TumRoundTrip) {
  const auto file = test::scratch_dir() / "t.txt";
  write_tum(file, sample());
  const Trajectory r = read_trajectory(file);
  ASSERT_EQ(r.size(), 5u);
  EXPECT_FALSE(r.indexed);
  for (size_t i = 0; i < 5; ++i) {
    EXPECT_NEAR(r.timestamps[i], sample().timestamps[i], 1e-6);
    EXPECT_LT((r.poses[i].matrix() - sample().poses[i].matrix()).norm(), 1e-8);
  }
}

TEST(TrajectoryIo, KittiRoundTripIsIndexed) {
  const auto file = test::scratch_dir() / "k.txt";
  write_kitti(file, sample());
  const Trajectory r = read_trajectory(file);
  ASSERT_EQ(r.size(), 5u);
  EXPECT_TRUE(r.indexed);
  EXPECT_DOUBLE_EQ(r.timestamps[3], 3.0);
  EXPECT_LT((r.poses[4].matrix() - sample().poses[4].matrix()).norm(), 1e-8);
}

TEST(TrajectoryIo, ErrorsNameFileAndLine) {
  const auto file = test::scratch_dir() / "bad.txt";
  test::write_text(file, "1 0 0 0 0 0 0 1\n2 0 0 0 0 0 1\n");
  try {
    read_trajectory(file);
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()), file.string() + ":2: expected 8 values 'timestamp tx ty tz qx qy qz qw', got 7");
  }
  test::write_text(file, "2 0 0 0 0 0 0 1\n1 0 0 0 0 0 0 1\n");
  EXPECT_THROW(read_trajectory(file), InputError);
  test::write_text(file, "1 0 0 0 0 0 0 3\n");
  EXPECT_THROW(read_trajectory(file), InputError);  // not a unit quaternion
  test::write_text(file, "# only a comment\n");
  EXPECT_THROW(read_trajectory(file), InputError);
}

}  // namespace
}  // namespace wardmap::slam::io
