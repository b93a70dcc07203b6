// A grid over the (undistorted) image holding keypoint indices, for radius searches during matching.
#pragma once

#include <Eigen/Core>
#include <vector>

namespace wardmap::slam {

class FeatureGrid {
 public:
  FeatureGrid() = default;
  // `points`: undistorted pixels; `levels`: pyramid level of each point.
  FeatureGrid(const std::vector<Eigen::Vector2d>& points, const std::vector<int>& levels, int width, int height,
              int cell_size = 20);
  // Indices of the points within `radius` (L-inf) of (x, y) whose level is in [min_level, max_level]
  // (max_level < 0: no upper bound), cell by cell (rows, then columns) and ascending within a cell:
  // the matchers keep the first of equally good candidates, so this order is part of the contract.
  std::vector<int> in_area(double x, double y, double radius, int min_level = 0, int max_level = -1) const;
  // The same into `out` (cleared first), for loops that reuse one buffer instead of allocating per query.
  void in_area(double x, double y, double radius, int min_level, int max_level, std::vector<int>& out) const;

 private:
  // One keypoint as a cell holds it: position and level beside the index, so that a query reads
  // each cell as one contiguous run.
  struct Entry {
    double x, y;
    int index;
    int level;
  };
  int cols_ = 0, rows_ = 0;
  double cell_ = 20;
  // Cell c holds entries_[start_[c] .. start_[c + 1]), in ascending keypoint index.
  std::vector<int> start_;
  std::vector<Entry> entries_;
};

}  // namespace wardmap::slam
