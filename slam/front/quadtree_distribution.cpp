#include "slam/front/quadtree_distribution.h"

#include <algorithm>
#include <array>
#include <cmath>

#include "slam/front/counting_sort.h"

namespace wardmap::slam {

namespace {

// A node's members are the range [begin, end) of one index array; a split partitions its range
// stably into the four quadrants' ranges, so a child lists its members in the parent's order.
struct Node {
  cv::Rect2f box;
  int begin = 0, end = 0;
  int size() const { return end - begin; }
  bool leaf() const { return size() <= 1 || box.width < 2.0f || box.height < 2.0f; }
};

// Splits a node into up to four non-empty children (quadrant order), appended to `out`.
void split(const Node& n, const std::vector<cv::Point2f>& pts, std::vector<int>& index, std::vector<int>& scratch,
           std::vector<unsigned char>& quadrant, std::vector<Node>& out) {
  const float hw = n.box.width / 2, hh = n.box.height / 2;
  const float mx = n.box.x + hw, my = n.box.y + hh;
  std::array<int, 4> count{};
  for (int i = n.begin; i < n.end; ++i) {
    const cv::Point2f& p = pts[static_cast<size_t>(index[static_cast<size_t>(i)])];
    const int q = (p.y >= my ? 2 : 0) + (p.x >= mx ? 1 : 0);
    quadrant[static_cast<size_t>(i)] = static_cast<unsigned char>(q);
    ++count[static_cast<size_t>(q)];
  }
  std::array<int, 4> start{};
  start[0] = n.begin;
  for (int q = 1; q < 4; ++q) start[q] = start[q - 1] + count[q - 1];
  std::array<int, 4> fill = start;
  for (int i = n.begin; i < n.end; ++i)
    scratch[static_cast<size_t>(fill[quadrant[static_cast<size_t>(i)]]++)] = index[static_cast<size_t>(i)];
  std::copy(scratch.begin() + n.begin, scratch.begin() + n.end, index.begin() + n.begin);
  for (int q = 0; q < 4; ++q) {
    if (count[static_cast<size_t>(q)] == 0) continue;
    Node c;
    c.box = cv::Rect2f(n.box.x + (q % 2) * hw, n.box.y + (q / 2) * hh, hw, hh);
    c.begin = start[static_cast<size_t>(q)];
    c.end = c.begin + count[static_cast<size_t>(q)];
    out.push_back(c);
  }
}

}  // namespace

std::vector<cv::KeyPoint> distribute_quadtree(const std::vector<cv::KeyPoint>& kps, const cv::Rect2f& region,
                                              int target) {
  if (kps.empty() || target <= 0) return {};
  const int n = static_cast<int>(kps.size());
  std::vector<cv::Point2f> pts(static_cast<size_t>(n));
  for (int k = 0; k < n; ++k) pts[static_cast<size_t>(k)] = kps[static_cast<size_t>(k)].pt;

  // Initial square-ish nodes side by side so that the first splits produce square cells.
  const int n_init = std::max(1, static_cast<int>(std::lround(region.width / std::max(region.height, 1.0f))));
  const float w = region.width / n_init;
  std::vector<int> column(static_cast<size_t>(n));
  for (int k = 0; k < n; ++k)
    column[static_cast<size_t>(k)] =
        std::clamp(static_cast<int>((pts[static_cast<size_t>(k)].x - region.x) / w), 0, n_init - 1);
  std::vector<int> column_start, index;
  counting_sort(column, n_init, column_start, index);
  std::vector<int> scratch(static_cast<size_t>(n));
  std::vector<unsigned char> quadrant(static_cast<size_t>(n));
  std::vector<Node> nodes;
  for (int i = 0; i < n_init; ++i) {
    Node node;
    node.box = cv::Rect2f(region.x + i * w, region.y, w, region.height);
    node.begin = column_start[static_cast<size_t>(i)];
    node.end = column_start[static_cast<size_t>(i) + 1];
    if (node.size() > 0) nodes.push_back(node);
  }

  std::vector<Node> next;
  while (static_cast<int>(nodes.size()) < target) {
    // Split the most populated nodes first so that the last, partial round refines the dense areas.
    std::stable_sort(nodes.begin(), nodes.end(), [](const Node& a, const Node& b) { return a.size() > b.size(); });
    next.clear();
    next.reserve(nodes.size() * 4);
    bool any_split = false;
    size_t i = 0;
    for (; i < nodes.size(); ++i) {
      const int remaining_count = static_cast<int>(next.size() + (nodes.size() - i));
      if (remaining_count >= target) break;
      if (nodes[i].leaf()) {
        next.push_back(nodes[i]);
        continue;
      }
      split(nodes[i], pts, index, scratch, quadrant, next);
      any_split = true;
    }
    for (; i < nodes.size(); ++i) next.push_back(nodes[i]);
    nodes.swap(next);
    if (!any_split) break;
  }

  std::vector<cv::KeyPoint> out;
  out.reserve(nodes.size());
  for (const Node& node : nodes) {
    int best = index[static_cast<size_t>(node.begin)];
    for (int m = node.begin; m < node.end; ++m) {
      const int k = index[static_cast<size_t>(m)];
      if (kps[static_cast<size_t>(k)].response > kps[static_cast<size_t>(best)].response) best = k;
    }
    out.push_back(kps[static_cast<size_t>(best)]);
  }
  return out;
}

}  // namespace wardmap::slam
