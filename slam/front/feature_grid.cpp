#include "slam/front/feature_grid.h"

#include <algorithm>
#include <cmath>

namespace wardmap::slam {

FeatureGrid::FeatureGrid(const std::vector<Eigen::Vector2d>& points, const std::vector<int>& levels, int width,
                         int height, int cell_size)
    : cols_(std::max(1, (width + cell_size - 1) / cell_size)),
      rows_(std::max(1, (height + cell_size - 1) / cell_size)),
      cell_(cell_size),
      cells_(static_cast<size_t>(cols_ * rows_)),
      points_(points),
      levels_(levels) {
  for (size_t i = 0; i < points.size(); ++i) {
    const int cx = static_cast<int>(std::floor(points[i].x() / cell_));
    const int cy = static_cast<int>(std::floor(points[i].y() / cell_));
    if (cx < 0 || cy < 0 || cx >= cols_ || cy >= rows_) continue;  // undistorted outside the image
    cells_[static_cast<size_t>(cy * cols_ + cx)].push_back(static_cast<int>(i));
  }
}

std::vector<int> FeatureGrid::in_area(double x, double y, double r, int min_level, int max_level) const {
  std::vector<int> out;
  in_area(x, y, r, min_level, max_level, out);
  return out;
}

void FeatureGrid::in_area(double x, double y, double r, int min_level, int max_level, std::vector<int>& out) const {
  out.clear();
  if (cells_.empty()) return;
  const int x0 = std::max(0, static_cast<int>(std::floor((x - r) / cell_)));
  const int x1 = std::min(cols_ - 1, static_cast<int>(std::floor((x + r) / cell_)));
  const int y0 = std::max(0, static_cast<int>(std::floor((y - r) / cell_)));
  const int y1 = std::min(rows_ - 1, static_cast<int>(std::floor((y + r) / cell_)));
  for (int cy = y0; cy <= y1; ++cy)
    for (int cx = x0; cx <= x1; ++cx)
      for (int i : cell(cx, cy)) {
        const int l = levels_[static_cast<size_t>(i)];
        if (l < min_level || (max_level >= 0 && l > max_level)) continue;
        const Eigen::Vector2d& p = points_[static_cast<size_t>(i)];
        if (std::abs(p.x() - x) <= r && std::abs(p.y() - y) <= r) out.push_back(i);
      }
}

}  // namespace wardmap::slam
