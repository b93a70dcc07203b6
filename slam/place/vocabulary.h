// A vocabulary tree of binary words for place recognition (bag of words, as DBoW2: Galvez-Lopez &
// Tardos 2012): ORB descriptors descend a k-ary tree of depth L by the nearest child centre (Hamming
// distance); the leaf reached is the descriptor's word. An image becomes a tf-idf weighted,
// L1-normalised bag of words, and two bags are compared with the L1 score. Training is in
// vocabulary_training.h, the file format in vocabulary_io.cpp.
#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <map>
#include <opencv2/core.hpp>
#include <string>
#include <utility>
#include <vector>

#include "slam/place/hamming.h"

namespace wardmap::slam::place {

using WordId = std::uint32_t;
using NodeId = std::uint32_t;
// (word, weight) sorted by word, each word once, weights > 0 summing to 1 (empty for no features).
using BowVector = std::vector<std::pair<WordId, double>>;
// Direct index: the features (row numbers) under each tree node of one depth, for matching
// restricted to features that share a node.
using FeatureVector = std::map<NodeId, std::vector<int>>;

class Vocabulary {
 public:
  Vocabulary() = default;
  // A tree in breadth-first order: node 0 is the root; the children of a node are contiguous and
  // come in node order, so `child_counts` alone gives the structure. Leaves are the words, numbered
  // in node order; `idf` has one weight per word. Throws std::invalid_argument when inconsistent.
  Vocabulary(int branching, int levels, std::vector<Descriptor> centres, std::vector<std::uint8_t> child_counts,
             std::vector<float> idf, std::uint64_t training_images);

  bool empty() const { return centres_.empty(); }
  int branching() const { return branching_; }
  int levels() const { return levels_; }
  std::size_t node_count() const { return centres_.size(); }
  std::size_t word_count() const { return idf_.size(); }
  std::uint64_t training_images() const { return training_images_; }
  // idf weight of a word: log(training images / training images holding the word).
  double idf(WordId word) const { return idf_.at(word); }

  // The word of one descriptor (32 bytes); `node_at_depth` (optional) receives the node passed at
  // depth `depth` on the way down (the leaf when the leaf is shallower).
  WordId word(const std::uint8_t* descriptor, int depth = 0, NodeId* node_at_depth = nullptr) const;
  // Bag of words of an image's descriptors (N x 32, CV_8U): tf-idf weights, L1-normalised; words
  // with idf 0 (seen in every training image) are left out. With `direct`, also the direct index at
  // tree depth `direct_depth` (1 = the root's children). Throws std::invalid_argument on a wrong type.
  BowVector transform(const cv::Mat& descriptors, FeatureVector* direct = nullptr, int direct_depth = 2) const;

  // Binary file: see vocabulary_io.cpp. save() writes through a temporary name and a rename;
  // load() throws InputError naming the file and the problem (missing, truncated, corrupted, wrong kind).
  std::string to_bytes() const;
  static Vocabulary from_bytes(const std::string& bytes, const std::string& source_name);
  void save(const std::filesystem::path& file) const;
  static Vocabulary load(const std::filesystem::path& file);

  // Tree access (for tests and tools).
  const Descriptor& centre(NodeId node) const { return centres_.at(node); }
  int child_count(NodeId node) const { return child_count_.at(node); }
  NodeId first_child(NodeId node) const { return first_child_.at(node); }
  int depth(NodeId node) const { return depth_.at(node); }

 private:
  int branching_ = 0, levels_ = 0;
  std::uint64_t training_images_ = 0;
  std::vector<Descriptor> centres_;         // per node (the root's is unused)
  std::vector<std::uint8_t> child_count_;   // per node, 0 for a leaf
  std::vector<NodeId> first_child_;         // per node
  std::vector<std::uint8_t> depth_;         // per node, root 0
  std::vector<std::int32_t> word_of_node_;  // per node, -1 for inner nodes
  std::vector<float> idf_;                  // per word
};

// DBoW2 L1 score (Galvez-Lopez & Tardos 2012): s = 1 - 0.5 |a - b|_1 for L1-normalised bags, in
// [0, 1]; computed over the shared words as 0.5 sum(|a_i| + |b_i| - |a_i - b_i|), so 0 for an empty bag.
double l1_score(const BowVector& a, const BowVector& b);

}  // namespace wardmap::slam::place
