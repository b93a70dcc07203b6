// Rotation consistency of a set of matches: the keypoint angle differences are binned and only the
// matches in the three most populated bins are kept (a rigid motion rotates every feature alike).
#pragma once

#include <cstddef>
#include <vector>

namespace wardmap::slam {

class RotationHistogram {
 public:
  explicit RotationHistogram(int bins = 30) : bins_(static_cast<std::size_t>(bins)) {}
  // angle1, angle2 in degrees; `match` is an id the caller uses to undo rejected matches.
  void add(float angle1, float angle2, int match);
  // The ids outside the three fullest bins (bins with less than a tenth of the fullest are dropped too).
  std::vector<int> rejected() const;

 private:
  std::vector<std::vector<int>> bins_;
};

}  // namespace wardmap::slam
