// The optical flow (tracking.flow_extend / _mono) under a time budget. The flow keeps map points
// alive longer and lowers the monocular drift, but costs 1.4-2.2x the tracking time: a fast host can
// afford it within the realtime target, a slow or loaded one cannot (docs/EXPERIMENTS.md, "The flow
// under a time budget"). This controller turns it on and off for whole windows of frames, since
// skipping it on single frames breaks the followed points' chains and loses most of its gain.
//
// Every `window` tracked frames it takes the median frame time of the window:
// - the flow on, and that median over the budget: off;
// - the flow off: on again when that median plus the flow's measured cost (the last on-window's median
//   less the first off-window's after it) fits the budget, or after `retry` off-windows in a row, to
//   measure its cost again (the host's load changes). A retry over the budget doubles the wait for
//   the next (each costs a window over it); a window on within the budget resets it to `retry`.
// It starts on, and again with each new submap (restart). A budget of 0 keeps the flow on for good
// (--deterministic runs: the choice must not depend on timing).
#pragma once

#include <vector>

namespace wardmap::slam {

class FlowBudget {
 public:
  FlowBudget(double budget_seconds, int window, int retry);

  // Whether the next frame runs the flow.
  bool active() const { return active_; }
  // One tracked frame's time (extraction and tracking), spent with the flow if active() was true.
  void record(double seconds);
  // A new map starts (a new submap): the flow on for its first window, whatever the budget said, as
  // for the first map (a young monocular map without it can lose its scale: docs/EXPERIMENTS.md).
  void restart();
  // Windows completed so far with the flow on and off.
  int windows_on() const { return windows_on_; }
  int windows_off() const { return windows_off_; }

 private:
  double budget_;
  int window_;
  int retry_;
  bool active_ = true;
  std::vector<double> samples_;
  double last_on_ = -1;   // median of the last on-window (s); -1: none yet
  double cost_ = -1;      // the flow's cost: last_on_ less the next off-window's median; -1: unknown
  int off_in_a_row_ = 0;  // off-windows since the flow was last on
  int retry_interval_;       // off-windows before the next retry
  bool retrying_ = false;    // the flow is on to measure its cost again
  int windows_on_ = 0, windows_off_ = 0;
};

}  // namespace wardmap::slam
