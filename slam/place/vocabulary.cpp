#include "slam/place/vocabulary.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <unordered_map>

namespace wardmap::slam::place {

namespace {

void require(bool ok, const std::string& problem) {
  if (!ok) throw std::invalid_argument(problem);
}

}  // namespace

Vocabulary::Vocabulary(int branching, int levels, std::vector<Descriptor> centres,
                       std::vector<std::uint8_t> child_counts, std::vector<float> idf, std::uint64_t training_images)
    : branching_(branching),
      levels_(levels),
      training_images_(training_images),
      centres_(std::move(centres)),
      child_count_(std::move(child_counts)),
      idf_(std::move(idf)) {
  require(branching_ >= 2 && branching_ <= 255, "branching " + std::to_string(branching_) + " is not in [2, 255]");
  require(levels_ >= 1 && levels_ <= 16, "levels " + std::to_string(levels_) + " is not in [1, 16]");
  require(!centres_.empty(), "the tree has no nodes");
  require(centres_.size() == child_count_.size(), "centres and child counts differ in number");
  const std::size_t n = centres_.size();
  first_child_.assign(n, 0);
  depth_.assign(n, 0);
  word_of_node_.assign(n, -1);
  std::size_t next = 1;  // breadth-first: the children of node i follow those of node i - 1
  std::int32_t words = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const int c = child_count_[i];
    require(c <= branching_, "node " + std::to_string(i) + " has " + std::to_string(c) +
                                 " children, more than the branching " + std::to_string(branching_));
    require(i == 0 || i < next, "node " + std::to_string(i) + " has no parent");
    if (c == 0) {
      word_of_node_[i] = words++;
      continue;
    }
    require(depth_[i] < levels_, "node " + std::to_string(i) + " has children below the last level");
    require(next + c <= n, "node " + std::to_string(i) + " names children beyond the " + std::to_string(n) + " nodes");
    first_child_[i] = static_cast<NodeId>(next);
    for (int j = 0; j < c; ++j) depth_[next + j] = static_cast<std::uint8_t>(depth_[i] + 1);
    next += c;
  }
  require(next == n, std::to_string(n - next) + " nodes have no parent");
  require(static_cast<std::size_t>(words) == idf_.size(),
          "the tree has " + std::to_string(words) + " leaves but " + std::to_string(idf_.size()) + " idf weights");
  for (std::size_t w = 0; w < idf_.size(); ++w)
    require(std::isfinite(idf_[w]) && idf_[w] >= 0,
            "idf weight of word " + std::to_string(w) + " is not a finite value >= 0");
}

WordId Vocabulary::word(const std::uint8_t* descriptor, int depth, NodeId* node_at_depth) const {
  NodeId node = 0;
  while (child_count_[node] > 0) {
    if (node_at_depth && depth_[node] == depth) *node_at_depth = node;
    const NodeId first = first_child_[node];
    NodeId best = first;
    int best_d = hamming_distance(descriptor, centres_[first].data());
    for (NodeId c = first + 1; c < first + child_count_[node]; ++c) {
      const int d = hamming_distance(descriptor, centres_[c].data());
      if (d < best_d) best_d = d, best = c;  // ties: the lower index, as in training
    }
    node = best;
  }
  if (node_at_depth && depth_[node] <= depth) *node_at_depth = node;
  return static_cast<WordId>(word_of_node_[node]);
}

BowVector Vocabulary::transform(const cv::Mat& descriptors, FeatureVector* direct, int direct_depth) const {
  if (direct) direct->clear();
  if (descriptors.empty()) return {};
  if (empty()) throw std::invalid_argument("transform: the vocabulary is empty");
  if (descriptors.type() != CV_8UC1 || descriptors.cols != kDescriptorBytes)
    throw std::invalid_argument("transform: descriptors must be N x 32 CV_8U (ORB), got " +
                                std::to_string(descriptors.rows) + " x " + std::to_string(descriptors.cols) +
                                " of type " + std::to_string(descriptors.type()));
  // tf-idf: each feature adds its word's idf; dividing by the total then gives tf x idf, L1-normalised.
  std::unordered_map<WordId, double> sum;
  double total = 0;
  for (int r = 0; r < descriptors.rows; ++r) {
    NodeId node = 0;
    const WordId w = word(descriptors.ptr<std::uint8_t>(r), direct_depth, direct ? &node : nullptr);
    if (direct) (*direct)[node].push_back(r);
    const double weight = idf_[w];
    if (weight <= 0) continue;
    sum[w] += weight;
    total += weight;
  }
  BowVector bow(sum.begin(), sum.end());
  std::sort(bow.begin(), bow.end());
  for (auto& [w, v] : bow) v /= total;
  return bow;
}

double l1_score(const BowVector& a, const BowVector& b) {
  double s = 0;
  auto i = a.begin(), j = b.begin();
  while (i != a.end() && j != b.end()) {
    if (i->first < j->first) {
      ++i;
    } else if (j->first < i->first) {
      ++j;
    } else {
      s += std::abs(i->second) + std::abs(j->second) - std::abs(i->second - j->second);
      ++i, ++j;
    }
  }
  return 0.5 * s;
}

}  // namespace wardmap::slam::place
