// Keyframe database for relocalisation: an inverted index from each word to the keyframes whose bag
// of words holds it. A query counts the words each keyframe shares with the query bag, keeps the
// keyframes sharing at least min_common_ratio x the most shared words, and ranks them by the L1
// score (after ORB-SLAM's DetectRelocalizationCandidates, Mur-Artal & Tardos 2017, without its
// covisibility-group accumulation: no covisibility graph is known here). Keyframes are plain ids.
#pragma once

#include <cstddef>
#include <cstdint>
#include <unordered_map>
#include <vector>

#include "slam/place/place_options.h"
#include "slam/place/vocabulary.h"

namespace wardmap::slam::place {

struct PlaceCandidate {
  std::uint64_t id = 0;
  double score = 0;  // L1 score in [0, 1]
};

class KeyframeDatabase {
 public:
  // Throws std::invalid_argument when the options are invalid.
  explicit KeyframeDatabase(const PlaceOptions& options = {});

  // Adds a keyframe (replacing an earlier one with the same id).
  void add(std::uint64_t id, BowVector bow);
  // Removes a keyframe; false when the id is not in the database.
  bool erase(std::uint64_t id);
  void clear();
  std::size_t size() const { return slot_of_.size(); }
  bool contains(std::uint64_t id) const { return slot_of_.count(id) > 0; }
  // The keyframe's bag of words, or nullptr.
  const BowVector* bow(std::uint64_t id) const;

  // Candidates for `bow`, best score first (ties: lower id first), at most max_results of them
  // (0: all), each scoring at least min_score.
  std::vector<PlaceCandidate> query(const BowVector& bow, std::size_t max_results, double min_score = 0.0) const;

 private:
  // Keyframes live in dense slots (reused after erase) so that a query counts shared words in a vector.
  struct Slot {
    std::uint64_t id = 0;
    BowVector bow;
    bool used = false;
  };
  PlaceOptions options_;
  std::vector<Slot> slots_;
  std::vector<std::uint32_t> free_slots_;
  std::unordered_map<std::uint64_t, std::uint32_t> slot_of_;
  std::unordered_map<WordId, std::vector<std::uint32_t>> inverted_;  // word -> slots of the keyframes holding it
};

}  // namespace wardmap::slam::place
