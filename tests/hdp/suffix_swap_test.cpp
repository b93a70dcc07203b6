#include "hdp/suffix_swap.h"

#include <gtest/gtest.h>

#include "tests/hdp/normal_model.h"

namespace wardmap::hdp {
namespace {

// Two neighbouring objects A (x = 0) and B (x = 2) seen together in each of 10 groups, one item each;
// the two items of a group cannot share a dish.
struct Neighbours {
  std::vector<std::vector<Eigen::VectorXd>> data;
  NormalModel model;
  Neighbours() : data(make()), model(data, 0.3, 5.0, Eigen::VectorXd::Constant(1, 1.0)) {
    for (int j = 0; j < 10; ++j) model.forbidden.push_back({{j, 0}, {j, 1}});
  }
  static std::vector<std::vector<Eigen::VectorXd>> make() {
    Gauss g(7);
    std::vector<std::vector<Eigen::VectorXd>> d;
    for (int j = 0; j < 10; ++j)
      d.push_back({Eigen::VectorXd::Constant(1, 0.0 + 0.3 * g()), Eigen::VectorXd::Constant(1, 2.0 + 0.3 * g())});
    return d;
  }
};

// Item 0 (A) in dish 0 and item 1 (B) in dish 1 up to group `cut`, the other way round after it.
std::vector<std::vector<int>> swapped_from(int cut) {
  std::vector<std::vector<int>> dish;
  for (int j = 0; j < 10; ++j) dish.push_back(j < cut ? std::vector<int>{0, 1} : std::vector<int>{1, 0});
  return dish;
}

TEST(SuffixSwap, RepairsNeighboursSwappedOverARunOfGroups) {
  const Neighbours n;
  auto dish = swapped_from(6);
  EXPECT_EQ(improve_by_suffix_swaps(n.model, dish, 2), 1);
  EXPECT_EQ(dish, swapped_from(10));  // A in dish 0 in every group
}

TEST(SuffixSwap, LeavesATrueStateAlone) {
  const Neighbours n;
  auto dish = swapped_from(10);
  EXPECT_EQ(improve_by_suffix_swaps(n.model, dish, 2), 0);
  EXPECT_EQ(dish, swapped_from(10));
}

TEST(SuffixSwap, SmallGainsAreLeft) {
  const Neighbours n;
  auto dish = swapped_from(6);
  SuffixSwapOptions o;
  o.min_gain = 1e6;
  EXPECT_EQ(improve_by_suffix_swaps(n.model, dish, 2, o), 0);
  EXPECT_EQ(dish, swapped_from(6));
}

TEST(SuffixSwap, NeverJoinsItemsThatCannotLink) {
  Neighbours n;
  n.model.forbidden.push_back({{2, 0}, {8, 0}});  // A's items of groups 2 and 8 are two objects
  auto dish = swapped_from(6);
  improve_by_suffix_swaps(n.model, dish, 2);
  EXPECT_NE(dish[2][0], dish[8][0]);
  for (int j = 0; j < 10; ++j) EXPECT_NE(dish[j][0], dish[j][1]);
}

}  // namespace
}  // namespace wardmap::hdp
