#include "slam/front/counting_sort.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <vector>

namespace wardmap::slam {
namespace {

// The counting sort against a stable sort of the kept indices by key, with the offsets counted out.
TEST(CountingSort, GroupsLikeAStableSortAndLeavesOutNegativeKeys) {
  std::mt19937 rng(11);
  for (int trial = 0; trial < 200; ++trial) {
    const int n_buckets = 1 + trial % 37;
    std::uniform_int_distribution<int> key(-3, n_buckets - 1), size(0, 400);
    std::vector<int> keys(static_cast<size_t>(size(rng)));
    for (int& k : keys) k = key(rng);

    std::vector<int> expected;
    for (size_t i = 0; i < keys.size(); ++i)
      if (keys[i] >= 0) expected.push_back(static_cast<int>(i));
    std::stable_sort(expected.begin(), expected.end(), [&](int p, int q) { return keys[p] < keys[q]; });

    std::vector<int> start{42}, order{7, 7, 7};  // stale contents must be overwritten
    counting_sort(keys, n_buckets, start, order);
    ASSERT_EQ(order, expected) << "trial " << trial;
    ASSERT_EQ(start.size(), static_cast<size_t>(n_buckets) + 1);
    EXPECT_EQ(start.front(), 0);
    for (int b = 0; b < n_buckets; ++b) {
      const int count = static_cast<int>(std::count(keys.begin(), keys.end(), b));
      ASSERT_EQ(start[b + 1] - start[b], count) << "trial " << trial << " bucket " << b;
      for (int p = start[b]; p < start[b + 1]; ++p) ASSERT_EQ(keys[order[p]], b);
    }
  }
}

TEST(CountingSort, EmptyInputGivesEmptyBuckets) {
  std::vector<int> start, order{1};
  counting_sort({}, 3, start, order);
  EXPECT_EQ(start, (std::vector<int>{0, 0, 0, 0}));
  EXPECT_TRUE(order.empty());
}

}  // namespace
}  // namespace wardmap::slam
