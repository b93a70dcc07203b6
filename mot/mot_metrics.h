// CLEAR-MOT metrics (Bernardin & Stiefelhagen 2008) from per-frame correspondences: the caller has
// already matched ground-truth objects to hypotheses in each frame; this counts misses, false
// positives, identity switches and MOTA.
#pragma once

#include <map>
#include <utility>
#include <vector>

namespace wardmap::mot {

struct FrameCorrespondences {
  std::vector<std::pair<int, int>> matches;  // (ground-truth id, hypothesis id)
  int misses = 0;                            // ground-truth objects with no hypothesis
  int false_positives = 0;                   // hypotheses with no ground-truth object
};

struct ClearMotResult {
  int frames = 0;
  int ground_truth = 0;  // sum over frames of matches + misses
  int matches = 0;
  int misses = 0;
  int false_positives = 0;
  int id_switches = 0;  // a gt id matched to a hypothesis other than the one it last had
  double mota = 0;      // 1 - (misses + false positives + id switches) / ground truth
};

class ClearMotAccumulator {
 public:
  void add_frame(const FrameCorrespondences& frame);
  const ClearMotResult& result() const { return result_; }

 private:
  ClearMotResult result_;
  std::map<int, int> last_hypothesis_;  // gt id -> hypothesis it was last matched to
};

// All frames at once.
ClearMotResult clear_mot(const std::vector<FrameCorrespondences>& frames);

}  // namespace wardmap::mot
