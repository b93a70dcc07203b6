#include "slam/front/feature_grid.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

namespace wardmap::slam {
namespace {

// What in_area must return: every index within `r` (L-inf) and the level range, by a full scan.
std::vector<int> brute_force(const std::vector<Eigen::Vector2d>& pts, const std::vector<int>& levels, double x,
                             double y, double r, int min_level, int max_level) {
  std::vector<int> out;
  for (size_t i = 0; i < pts.size(); ++i) {
    if (pts[i].x() < 0 || pts[i].y() < 0 || pts[i].x() >= 640 || pts[i].y() >= 480) continue;  // not gridded
    if (levels[i] < min_level || (max_level >= 0 && levels[i] > max_level)) continue;
    if (std::abs(pts[i].x() - x) <= r && std::abs(pts[i].y() - y) <= r) out.push_back(static_cast<int>(i));
  }
  return out;
}

TEST(FeatureGrid, InAreaFindsExactlyThePointsABruteForceScanFinds) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> ux(-15, 655), uy(-15, 495), ur(0.5, 60);
  std::uniform_int_distribution<int> ul(0, 7);
  std::vector<Eigen::Vector2d> pts;
  std::vector<int> levels;
  for (int i = 0; i < 1500; ++i) {  // some undistorted just outside the image, as near a lens's border
    pts.emplace_back(ux(rng), uy(rng));
    levels.push_back(ul(rng));
  }
  pts.emplace_back(40.0, 40.0);  // on a cell corner, and a duplicate position
  levels.push_back(0);
  pts.emplace_back(40.0, 40.0);
  levels.push_back(3);
  const FeatureGrid grid(pts, levels, 640, 480);
  int non_empty = 0;
  std::vector<int> reused{99};  // the buffer variant clears what it is given
  for (int q = 0; q < 3000; ++q) {
    // Queries over and beyond the image (areas wholly outside it included).
    const double x = q == 0 ? 40.0 : std::uniform_real_distribution<double>(-100, 740)(rng);
    const double y = q == 0 ? 40.0 : std::uniform_real_distribution<double>(-100, 580)(rng);
    const double r = q == 0 ? 0.0 : ur(rng);
    const int lo = q % 3 == 0 ? 0 : ul(rng);
    const int hi = q % 4 == 0 ? -1 : lo + ul(rng) / 2;
    std::vector<int> got = grid.in_area(x, y, r, lo, hi);
    std::sort(got.begin(), got.end());
    const std::vector<int> want = brute_force(pts, levels, x, y, r, lo, hi);
    ASSERT_EQ(got, want) << "query " << q << " at (" << x << ", " << y << ") r " << r << " levels " << lo << ".."
                         << hi;
    grid.in_area(x, y, r, lo, hi, reused);
    std::sort(reused.begin(), reused.end());
    ASSERT_EQ(reused, want) << "query " << q;
    if (!want.empty()) ++non_empty;
  }
  EXPECT_GT(non_empty, 1000);  // the queries did hit points
  EXPECT_EQ(grid.in_area(40.0, 40.0, 0.0).size(), 2u);
  EXPECT_TRUE(FeatureGrid().in_area(10, 10, 5).empty());
}

TEST(FeatureGrid, InAreaListsIndicesCellByCellInAscendingOrderWithinACell) {
  // The matchers take the first of equally good candidates, so the order is part of the contract.
  const std::vector<Eigen::Vector2d> pts{{25, 5}, {5, 5}, {6, 6}, {45, 25}, {7, 25}, {26, 6}};
  const std::vector<int> levels(pts.size(), 0);
  const FeatureGrid grid(pts, levels, 60, 40);
  EXPECT_EQ(grid.in_area(25, 20, 25), (std::vector<int>{1, 2, 0, 5, 4, 3}));
}

}  // namespace
}  // namespace wardmap::slam
