#include "slam/front/quadtree_distribution.h"

#include <algorithm>
#include <cmath>

namespace wardmap::slam {

namespace {

struct Node {
  cv::Rect2f box;
  std::vector<int> members;
  bool leaf() const { return members.size() <= 1 || box.width < 2.0f || box.height < 2.0f; }
};

// Splits a node into up to four non-empty children.
void split(const Node& n, const std::vector<cv::KeyPoint>& kps, std::vector<Node>& out) {
  const float hw = n.box.width / 2, hh = n.box.height / 2;
  Node c[4];
  for (int i = 0; i < 4; ++i) c[i].box = cv::Rect2f(n.box.x + (i % 2) * hw, n.box.y + (i / 2) * hh, hw, hh);
  for (int m : n.members) {
    const cv::Point2f& p = kps[m].pt;
    const int ix = p.x >= n.box.x + hw ? 1 : 0;
    const int iy = p.y >= n.box.y + hh ? 1 : 0;
    c[iy * 2 + ix].members.push_back(m);
  }
  for (auto& ch : c)
    if (!ch.members.empty()) out.push_back(std::move(ch));
}

}  // namespace

std::vector<cv::KeyPoint> distribute_quadtree(const std::vector<cv::KeyPoint>& kps, const cv::Rect2f& region,
                                              int target) {
  if (kps.empty() || target <= 0) return {};
  // Initial square-ish nodes side by side so that the first splits produce square cells.
  const int n_init = std::max(1, static_cast<int>(std::lround(region.width / std::max(region.height, 1.0f))));
  const float w = region.width / n_init;
  std::vector<Node> nodes(n_init);
  for (int i = 0; i < n_init; ++i) nodes[i].box = cv::Rect2f(region.x + i * w, region.y, w, region.height);
  for (int k = 0; k < static_cast<int>(kps.size()); ++k) {
    const int i = std::clamp(static_cast<int>((kps[k].pt.x - region.x) / w), 0, n_init - 1);
    nodes[i].members.push_back(k);
  }
  nodes.erase(std::remove_if(nodes.begin(), nodes.end(), [](const Node& n) { return n.members.empty(); }), nodes.end());

  while (static_cast<int>(nodes.size()) < target) {
    // Split the most populated nodes first so that the last, partial round refines the dense areas.
    std::stable_sort(nodes.begin(), nodes.end(),
                     [](const Node& a, const Node& b) { return a.members.size() > b.members.size(); });
    std::vector<Node> next;
    next.reserve(nodes.size() * 4);
    bool any_split = false;
    size_t i = 0;
    for (; i < nodes.size(); ++i) {
      const int remaining_count = static_cast<int>(next.size() + (nodes.size() - i));
      if (remaining_count >= target) break;
      if (nodes[i].leaf()) {
        next.push_back(std::move(nodes[i]));
        continue;
      }
      split(nodes[i], kps, next);
      any_split = true;
    }
    for (; i < nodes.size(); ++i) next.push_back(std::move(nodes[i]));
    nodes.swap(next);
    if (!any_split) break;
  }

  std::vector<cv::KeyPoint> out;
  out.reserve(nodes.size());
  for (const Node& n : nodes) {
    int best = n.members.front();
    for (int m : n.members)
      if (kps[m].response > kps[best].response) best = m;
    out.push_back(kps[best]);
  }
  return out;
}

}  // namespace wardmap::slam
