#include "slam/front/feature_grid.h"

#include <algorithm>
#include <cmath>

#include "slam/front/counting_sort.h"

namespace wardmap::slam {

FeatureGrid::FeatureGrid(const std::vector<Eigen::Vector2d>& points, const std::vector<int>& levels, int width,
                         int height, int cell_size)
    : cols_(std::max(1, (width + cell_size - 1) / cell_size)),
      rows_(std::max(1, (height + cell_size - 1) / cell_size)),
      cell_(cell_size) {
  std::vector<int> cell_of(points.size(), -1);
  for (size_t i = 0; i < points.size(); ++i) {
    const int cx = static_cast<int>(std::floor(points[i].x() / cell_));
    const int cy = static_cast<int>(std::floor(points[i].y() / cell_));
    if (cx < 0 || cy < 0 || cx >= cols_ || cy >= rows_) continue;  // undistorted outside the image
    cell_of[i] = cy * cols_ + cx;
  }
  std::vector<int> order;
  counting_sort(cell_of, cols_ * rows_, start_, order);
  entries_.resize(order.size());
  for (size_t p = 0; p < order.size(); ++p) {
    const size_t i = static_cast<size_t>(order[p]);
    entries_[p] = {points[i].x(), points[i].y(), order[p], levels[i]};
  }
}

std::vector<int> FeatureGrid::in_area(double x, double y, double r, int min_level, int max_level) const {
  std::vector<int> out;
  in_area(x, y, r, min_level, max_level, out);
  return out;
}

void FeatureGrid::in_area(double x, double y, double r, int min_level, int max_level, std::vector<int>& out) const {
  out.clear();
  if (entries_.empty()) return;
  const int x0 = std::max(0, static_cast<int>(std::floor((x - r) / cell_)));
  const int x1 = std::min(cols_ - 1, static_cast<int>(std::floor((x + r) / cell_)));
  const int y0 = std::max(0, static_cast<int>(std::floor((y - r) / cell_)));
  const int y1 = std::min(rows_ - 1, static_cast<int>(std::floor((y + r) / cell_)));
  if (x0 > x1 || y0 > y1) return;  // the area lies outside the image
  for (int cy = y0; cy <= y1; ++cy) {
    const int row = cy * cols_;
    const Entry* e = entries_.data() + start_[static_cast<size_t>(row + x0)];
    const Entry* end = entries_.data() + start_[static_cast<size_t>(row + x1 + 1)];
    for (; e != end; ++e) {  // the cells x0..x1 of a row are one run
      if (e->level < min_level || (max_level >= 0 && e->level > max_level)) continue;
      if (std::abs(e->x - x) <= r && std::abs(e->y - y) <= r) out.push_back(e->index);
    }
  }
}

}  // namespace wardmap::slam
