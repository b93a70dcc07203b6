// Training of the vocabulary tree: hierarchical k-majority (k-means for binary descriptors, Grana
// et al. 2013, as DBoW2 / ORB-SLAM vocabularies): at each node, k centres seeded by k-means++
// (Arthur & Vassilvitskii 2007) with Hamming distances, descriptors assigned to the nearest centre,
// centres moved to the bitwise majority of their members; repeated down to L levels. Then the idf
// weight of every word over the training images. Deterministic for a given seed.
#pragma once

#include <cstdint>
#include <opencv2/core.hpp>
#include <random>
#include <vector>

#include "slam/place/place_options.h"
#include "slam/place/vocabulary.h"

namespace wardmap::slam::place {

// Bitwise majority of the members: bit b is set when more than half of them have it set.
Descriptor majority_centre(const std::vector<Descriptor>& points, const std::vector<int>& members);
// Index of the centre nearest to d in Hamming distance; ties go to the lower index.
int nearest_centre(const std::uint8_t* d, const std::vector<Descriptor>& centres);

struct Clustering {
  std::vector<Descriptor> centres;  // at most k; fewer when the points hold fewer distinct descriptors
  std::vector<int> assignment;      // per point: the index of its nearest centre (none left empty)
};
// k-majority clustering of `points`. With at most k distinct points, each distinct point is a centre.
Clustering k_majority(const std::vector<Descriptor>& points, int k, int max_iterations, std::mt19937& rng);

// Trains a vocabulary on the descriptors of a set of images (one N x 32 CV_8U matrix per image; empty
// matrices count as images without features). Throws std::invalid_argument on bad options or input.
Vocabulary train_vocabulary(const std::vector<cv::Mat>& per_image_descriptors, const PlaceOptions& options,
                            std::uint32_t seed);

}  // namespace wardmap::slam::place
