// Options of place recognition (vocabulary training and keyframe queries), with the defaults of
// DBoW2 / ORB-SLAM where they give one, validated in one place.
#pragma once

namespace wardmap::slam::place {

// How PlaceOptions::validate's messages name the options: their keys, or a command's flags.
struct PlaceOptionNames {
  const char* branching = "place.branching";
  const char* levels = "place.levels";
  const char* max_iterations = "place.max_iterations";
};

struct PlaceOptions {
  int branching = 10;             // place.branching: k, children per vocabulary node
  int levels = 4;                 // place.levels: L, depth of the vocabulary tree (at most k^L words)
  int max_iterations = 10;        // place.max_iterations: k-majority rounds per node
  double min_common_ratio = 0.8;  // place.min_common_ratio: candidates share >= this x the most shared words
  // Throws std::invalid_argument naming the option (`names`) and the allowed range.
  void validate(const PlaceOptionNames& names) const;
  void validate() const;
};

}  // namespace wardmap::slam::place
