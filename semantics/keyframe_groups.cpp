#include "semantics/keyframe_groups.h"

#include <cmath>

namespace wardmap::semantics {

bool KeyframeSelector::accept(const slam::SE3& T) {
  ++since_last_;
  bool take = !has_last_;
  if (!take) {
    const slam::SE3 d = last_.inverse() * T;
    const double moved = d.translation().norm(), turned = slam::rotation_angle(d.rotation()) * 180.0 / M_PI;
    const bool still = moved < options_.still_translation && turned < options_.still_rotation_deg;
    take = moved >= options_.min_translation || turned >= options_.min_rotation_deg ||
           (since_last_ >= options_.max_interval && !still);
  }
  if (take) {
    has_last_ = true;
    last_ = T;
    since_last_ = 0;
  }
  return take;
}

std::vector<int> KeyframeGrouper::add_keyframe(int keyframe) {
  keyframes_.push_back(keyframe);
  std::vector<int> done;
  const size_t M = static_cast<size_t>(options_.size), step = static_cast<size_t>(options_.size - options_.overlap);
  while (keyframes_.size() >= next_start_ + M) {
    groups_.emplace_back(keyframes_.begin() + next_start_, keyframes_.begin() + next_start_ + M);
    done.push_back(static_cast<int>(groups_.size()) - 1);
    next_start_ += step;
  }
  return done;
}

int KeyframeGrouper::flush() {
  // The open group holds the keyframes after the last complete group's shared ones; it is only
  // worth a group when it has keyframes no complete group covers.
  const size_t covered = groups_.empty() ? 0 : next_start_ + static_cast<size_t>(options_.overlap);
  if (keyframes_.size() <= covered || next_start_ >= keyframes_.size()) return -1;
  groups_.emplace_back(keyframes_.begin() + next_start_, keyframes_.end());
  next_start_ = keyframes_.size();
  return static_cast<int>(groups_.size()) - 1;
}

}  // namespace wardmap::semantics
