#include "slam/front/flow_budget.h"

#include <algorithm>

namespace wardmap::slam {

FlowBudget::FlowBudget(double budget_seconds, int window, int retry)
    : budget_(budget_seconds), window_(std::max(1, window)), retry_(std::max(1, retry)), retry_interval_(retry_) {
  samples_.reserve(static_cast<size_t>(window_));
}

void FlowBudget::record(double seconds) {
  if (budget_ <= 0) return;
  samples_.push_back(seconds);
  if (samples_.size() < static_cast<size_t>(window_)) return;
  std::nth_element(samples_.begin(), samples_.begin() + static_cast<long>(samples_.size() / 2), samples_.end());
  const double median = samples_[samples_.size() / 2];
  samples_.clear();
  if (active_) {
    ++windows_on_;
    last_on_ = median;
    cost_ = -1;  // measured again by the next off-window
    if (median > budget_) {
      active_ = false;
      off_in_a_row_ = 0;
      // A retry that failed: wait twice as long before the next (each costs a window over the budget).
      if (retrying_) retry_interval_ = std::min(2 * retry_interval_, 1 << 20);
    } else {
      retry_interval_ = retry_;
    }
    retrying_ = false;
    return;
  }
  ++windows_off_;
  ++off_in_a_row_;
  if (cost_ < 0 && last_on_ >= 0) cost_ = std::max(0.0, last_on_ - median);
  if (cost_ >= 0 && median + cost_ <= budget_) {
    active_ = true;
  } else if (off_in_a_row_ >= retry_interval_) {
    active_ = retrying_ = true;
  }
}

void FlowBudget::restart() {
  samples_.clear();
  if (!active_) off_in_a_row_ = 0;
  active_ = true;
  retrying_ = false;
}

}  // namespace wardmap::slam
