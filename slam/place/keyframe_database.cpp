#include "slam/place/keyframe_database.h"

#include <algorithm>

namespace wardmap::slam::place {

KeyframeDatabase::KeyframeDatabase(const PlaceOptions& options) : options_(options) { options_.validate(); }

void KeyframeDatabase::add(std::uint64_t id, BowVector bow) {
  erase(id);
  std::uint32_t slot;
  if (free_slots_.empty()) {
    slot = static_cast<std::uint32_t>(slots_.size());
    slots_.emplace_back();
  } else {
    slot = free_slots_.back();
    free_slots_.pop_back();
  }
  for (const auto& entry : bow) inverted_[entry.first].push_back(slot);
  slots_[slot] = {id, std::move(bow), true};
  slot_of_.emplace(id, slot);
}

bool KeyframeDatabase::erase(std::uint64_t id) {
  const auto it = slot_of_.find(id);
  if (it == slot_of_.end()) return false;
  const std::uint32_t slot = it->second;
  for (const auto& entry : slots_[slot].bow) {
    const auto list = inverted_.find(entry.first);
    if (list == inverted_.end()) continue;
    auto& s = list->second;
    s.erase(std::remove(s.begin(), s.end(), slot), s.end());
    if (s.empty()) inverted_.erase(list);
  }
  slots_[slot] = Slot{};
  free_slots_.push_back(slot);
  slot_of_.erase(it);
  return true;
}

void KeyframeDatabase::clear() {
  slots_.clear();
  free_slots_.clear();
  slot_of_.clear();
  inverted_.clear();
}

const BowVector* KeyframeDatabase::bow(std::uint64_t id) const {
  const auto it = slot_of_.find(id);
  return it == slot_of_.end() ? nullptr : &slots_[it->second].bow;
}

std::vector<PlaceCandidate> KeyframeDatabase::query(const BowVector& bow, std::size_t max_results,
                                                    double min_score) const {
  // Words shared with each keyframe, through the inverted index.
  std::vector<int> shared(slots_.size(), 0);
  for (const auto& entry : bow) {
    const auto list = inverted_.find(entry.first);
    if (list == inverted_.end()) continue;
    for (std::uint32_t slot : list->second) ++shared[slot];
  }
  const int most = shared.empty() ? 0 : *std::max_element(shared.begin(), shared.end());
  if (most == 0) return {};
  // ORB-SLAM: keep the keyframes sharing at least 0.8 x the most shared words.
  const int min_common = std::max(1, static_cast<int>(options_.min_common_ratio * most));

  std::vector<PlaceCandidate> out;
  for (std::size_t slot = 0; slot < slots_.size(); ++slot) {
    if (shared[slot] < min_common) continue;
    const double s = l1_score(bow, slots_[slot].bow);
    if (s >= min_score) out.push_back({slots_[slot].id, s});
  }
  std::sort(out.begin(), out.end(), [](const PlaceCandidate& a, const PlaceCandidate& b) {
    return a.score != b.score ? a.score > b.score : a.id < b.id;
  });
  if (max_results > 0 && out.size() > max_results) out.resize(max_results);
  return out;
}

}  // namespace wardmap::slam::place
