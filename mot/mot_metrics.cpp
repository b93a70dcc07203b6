#include "mot/mot_metrics.h"

namespace wardmap::mot {

void ClearMotAccumulator::add_frame(const FrameCorrespondences& frame) {
  ClearMotResult& r = result_;
  ++r.frames;
  r.matches += static_cast<int>(frame.matches.size());
  r.misses += frame.misses;
  r.false_positives += frame.false_positives;
  r.ground_truth += static_cast<int>(frame.matches.size()) + frame.misses;
  for (const auto& [gt, hyp] : frame.matches) {
    auto it = last_hypothesis_.find(gt);
    if (it != last_hypothesis_.end()) {
      if (it->second != hyp) ++r.id_switches;
    }
    last_hypothesis_[gt] = hyp;
  }
  r.mota = r.ground_truth > 0 ? 1.0 - static_cast<double>(r.misses + r.false_positives + r.id_switches) / r.ground_truth
                              : 0.0;
}

ClearMotResult clear_mot(const std::vector<FrameCorrespondences>& frames) {
  ClearMotAccumulator acc;
  for (const auto& f : frames) acc.add_frame(f);
  return acc.result();
}

}  // namespace wardmap::mot
