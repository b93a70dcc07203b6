// Keyframe selection from known poses, and keyframe groups of M adjacent keyframes with j shared
// between neighbours (Assoc. III-A.1, Fig. 3).
#pragma once

#include <vector>

#include "semantics/options.h"
#include "slam/core/se3.h"

namespace wardmap::semantics {

// Incremental keyframe selection on known camera poses (--poses gt).
class KeyframeSelector {
 public:
  explicit KeyframeSelector(const KeyframeSelectionOptions& o) : options_(o) {}
  // True when the frame with pose T_wc becomes a keyframe.
  bool accept(const slam::SE3& T_wc);

 private:
  KeyframeSelectionOptions options_;
  bool has_last_ = false;
  slam::SE3 last_;
  int since_last_ = 0;
};

// Group n holds keyframes [n (M - j), n (M - j) + M). Groups are formed as keyframes arrive: the
// caller adds keyframe indices and is told when a group is complete.
class KeyframeGrouper {
 public:
  explicit KeyframeGrouper(const GroupOptions& o) : options_(o) {}
  // Adds the next keyframe (indices increase); returns the indices of the groups completed by it.
  std::vector<int> add_keyframe(int keyframe);
  // Completes the last partial group (end of sequence); returns its index or -1 when none is open.
  int flush();
  // Keyframes of group n (valid once the group is complete).
  const std::vector<int>& group(int n) const { return groups_.at(n); }
  int num_groups() const { return static_cast<int>(groups_.size()); }

 private:
  GroupOptions options_;
  std::vector<int> keyframes_;           // all keyframes so far
  std::vector<std::vector<int>> groups_;  // completed groups
  size_t next_start_ = 0;                 // index into keyframes_ where the next group starts
};

}  // namespace wardmap::semantics
