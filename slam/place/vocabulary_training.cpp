#include "slam/place/vocabulary_training.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <deque>
#include <numeric>
#include <stdexcept>
#include <string>

namespace wardmap::slam::place {

namespace {

// Uniform draws from the raw mt19937 output (fully specified by the standard), so that a seed gives
// the same vocabulary with every standard library; std::uniform_*_distribution is not portable.
std::size_t uniform_index(std::mt19937& rng, std::size_t n) {
  return static_cast<std::size_t>((static_cast<std::uint64_t>(rng()) * n) >> 32);
}
double uniform01(std::mt19937& rng) { return rng() * (1.0 / 4294967296.0); }

std::vector<int> assign(const std::vector<Descriptor>& points, const std::vector<Descriptor>& centres) {
  std::vector<int> a(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) a[i] = nearest_centre(points[i].data(), centres);
  return a;
}

// k-means++ seeding with D(x)^2 sampling in Hamming distance; stops early when every point is a centre.
std::vector<Descriptor> seed_centres(const std::vector<Descriptor>& points, int k, std::mt19937& rng) {
  const std::size_t n = points.size();
  std::vector<Descriptor> centres{points[uniform_index(rng, n)]};
  std::vector<double> d2(n);
  for (std::size_t i = 0; i < n; ++i) {
    const double d = hamming_distance(points[i].data(), centres[0].data());
    d2[i] = d * d;
  }
  while (static_cast<int>(centres.size()) < k) {
    const double total = std::accumulate(d2.begin(), d2.end(), 0.0);
    if (total <= 0) break;  // fewer than k distinct descriptors
    const double r = uniform01(rng) * total;
    double acc = 0;
    std::size_t pick = n, last_positive = 0;
    for (std::size_t i = 0; i < n; ++i) {
      if (d2[i] <= 0) continue;
      last_positive = i;
      acc += d2[i];
      if (acc > r) {
        pick = i;
        break;
      }
    }
    if (pick == n) pick = last_positive;  // rounding at the end of the sum
    centres.push_back(points[pick]);
    for (std::size_t i = 0; i < n; ++i) {
      const double d = hamming_distance(points[i].data(), points[pick].data());
      d2[i] = std::min(d2[i], d * d);
    }
  }
  return centres;
}

// Drops centres no point is assigned to, renumbering the assignment.
void drop_empty(Clustering& c) {
  std::vector<int> count(c.centres.size(), 0), renumber(c.centres.size(), -1);
  for (int a : c.assignment) ++count[a];
  std::vector<Descriptor> kept;
  for (std::size_t j = 0; j < c.centres.size(); ++j)
    if (count[j] > 0) renumber[j] = static_cast<int>(kept.size()), kept.push_back(c.centres[j]);
  for (int& a : c.assignment) a = renumber[a];
  c.centres = std::move(kept);
}

}  // namespace

Descriptor majority_centre(const std::vector<Descriptor>& points, const std::vector<int>& members) {
  int count[kDescriptorBytes * 8] = {};
  for (int m : members) {
    const Descriptor& d = points[m];
    for (int b = 0; b < kDescriptorBytes; ++b)
      for (int j = 0; j < 8; ++j) count[8 * b + j] += (d[b] >> j) & 1;
  }
  Descriptor c{};
  const int n = static_cast<int>(members.size());
  for (int b = 0; b < kDescriptorBytes; ++b)
    for (int j = 0; j < 8; ++j)
      if (2 * count[8 * b + j] > n) c[b] |= static_cast<std::uint8_t>(1u << j);
  return c;
}

int nearest_centre(const std::uint8_t* d, const std::vector<Descriptor>& centres) {
  int best = 0, best_d = hamming_distance(d, centres[0].data());
  for (std::size_t j = 1; j < centres.size(); ++j) {
    const int dj = hamming_distance(d, centres[j].data());
    if (dj < best_d) best_d = dj, best = static_cast<int>(j);
  }
  return best;
}

Clustering k_majority(const std::vector<Descriptor>& points, int k, int max_iterations, std::mt19937& rng) {
  Clustering c;
  if (points.empty()) return c;
  if (k < 1) throw std::invalid_argument("k_majority: k must be >= 1");
  c.centres = seed_centres(points, k, rng);
  c.assignment = assign(points, c.centres);
  drop_empty(c);
  for (int it = 0; it < max_iterations; ++it) {
    std::vector<std::vector<int>> members(c.centres.size());
    for (std::size_t i = 0; i < points.size(); ++i) members[c.assignment[i]].push_back(static_cast<int>(i));
    for (std::size_t j = 0; j < c.centres.size(); ++j) c.centres[j] = majority_centre(points, members[j]);
    std::vector<int> next = assign(points, c.centres);
    const bool changed = next != c.assignment;
    c.assignment = std::move(next);
    drop_empty(c);
    if (!changed) break;
  }
  return c;
}

Vocabulary train_vocabulary(const std::vector<cv::Mat>& per_image_descriptors, const PlaceOptions& options,
                            std::uint32_t seed) {
  options.validate();
  std::vector<Descriptor> all;
  for (std::size_t i = 0; i < per_image_descriptors.size(); ++i) {
    const cv::Mat& m = per_image_descriptors[i];
    if (m.empty()) continue;
    if (m.type() != CV_8UC1 || m.cols != kDescriptorBytes)
      throw std::invalid_argument("train_vocabulary: descriptors of image " + std::to_string(i) +
                                  " are not N x 32 CV_8U (ORB)");
    for (int r = 0; r < m.rows; ++r) {
      Descriptor d;
      std::memcpy(d.data(), m.ptr<std::uint8_t>(r), kDescriptorBytes);
      all.push_back(d);
    }
  }
  if (all.empty()) throw std::invalid_argument("train_vocabulary: no descriptors to train on");

  // Breadth-first: nodes are split in index order and their children appended together, which is
  // the layout Vocabulary expects.
  std::mt19937 rng(seed);
  std::vector<Descriptor> centres(1);
  std::vector<std::uint8_t> child_counts(1, 0);
  std::vector<int> depth(1, 0);
  struct Work {
    NodeId node;
    std::vector<int> members;
  };
  std::deque<Work> queue;
  queue.push_back({0, std::vector<int>(all.size())});
  std::iota(queue.back().members.begin(), queue.back().members.end(), 0);
  while (!queue.empty()) {
    Work w = std::move(queue.front());
    queue.pop_front();
    if (depth[w.node] >= options.levels || w.members.size() <= 1) continue;
    std::vector<Descriptor> points(w.members.size());
    for (std::size_t i = 0; i < w.members.size(); ++i) points[i] = all[w.members[i]];
    const Clustering c = k_majority(points, options.branching, options.max_iterations, rng);
    if (c.centres.size() <= 1) continue;  // all members identical: a leaf
    child_counts[w.node] = static_cast<std::uint8_t>(c.centres.size());
    const std::size_t first = centres.size();
    std::vector<std::vector<int>> members(c.centres.size());
    for (std::size_t i = 0; i < points.size(); ++i) members[c.assignment[i]].push_back(w.members[i]);
    for (std::size_t j = 0; j < c.centres.size(); ++j) {
      centres.push_back(c.centres[j]);
      child_counts.push_back(0);
      depth.push_back(depth[w.node] + 1);
      queue.push_back({static_cast<NodeId>(first + j), std::move(members[j])});
    }
  }

  // idf_i = log(N / n_i) over the N training images, n_i of them holding word i (DBoW2 tf-idf).
  std::size_t words = 0;
  for (auto c : child_counts) words += c == 0;
  const Vocabulary tree(options.branching, options.levels, centres, child_counts, std::vector<float>(words, 1.0f), 0);
  std::vector<std::size_t> images_with(words, 0);
  std::vector<std::size_t> last_image(words, static_cast<std::size_t>(-1));
  for (std::size_t i = 0; i < per_image_descriptors.size(); ++i) {
    const cv::Mat& m = per_image_descriptors[i];
    for (int r = 0; r < m.rows; ++r) {
      const WordId w = tree.word(m.ptr<std::uint8_t>(r));
      if (last_image[w] != i) last_image[w] = i, ++images_with[w];
    }
  }
  const double n_images = static_cast<double>(per_image_descriptors.size());
  std::vector<float> idf(words);
  for (std::size_t w = 0; w < words; ++w)
    idf[w] = static_cast<float>(std::log(n_images / static_cast<double>(std::max<std::size_t>(images_with[w], 1))));
  return Vocabulary(options.branching, options.levels, std::move(centres), std::move(child_counts), std::move(idf),
                    per_image_descriptors.size());
}

}  // namespace wardmap::slam::place
