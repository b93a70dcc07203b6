// Trajectory evaluation as ../docs/EVALUATION.md defines it: association by time (or frame index),
// Umeyama alignment (Sim(3) monocular, SE(3) RGB-D / stereo, or none), ATE, RPE, tracking rate.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "slam/core/sim3.h"
#include "slam/core/trajectory.h"

namespace wardmap::slam::eval {

enum class Alignment { Sim3, SE3, None };
Alignment parse_alignment(const std::string& name);  // "sim3" | "se3" | "none"; throws std::invalid_argument
std::string to_string(Alignment a);

struct AssociationOptions {
  double max_dt = 0.02;   // seconds
  bool by_index = false;  // pair the i-th poses (forced when either trajectory is indexed)
};

// Pairs (gt index, est index): each estimate with the closest ground truth within max_dt, each
// ground-truth pose used at most once (closest wins).
std::vector<std::pair<size_t, size_t>> associate(const Trajectory& gt, const Trajectory& est,
                                                 const AssociationOptions& options);

struct ErrorStats {
  double rmse = 0, mean = 0, median = 0, max = 0, min = 0, std = 0;
};
ErrorStats error_stats(std::vector<double> errors);

struct AteResult {
  size_t pairs = 0;
  Alignment alignment = Alignment::Sim3;
  Sim3 transform;            // maps estimate positions onto the ground truth
  double scale = 1.0;
  ErrorStats stats;          // metres
  std::vector<double> errors;  // per pair, metres
};
// Throws std::invalid_argument with fewer than 3 pairs (alignment undefined) for Sim3/SE3.
AteResult compute_ate(const Trajectory& gt, const Trajectory& est, const std::vector<std::pair<size_t, size_t>>& pairs,
                      Alignment alignment);

struct RpeResult {
  int delta = 1;            // frame gap between the two poses of each relative motion
  size_t count = 0;
  ErrorStats translation;   // metres (estimate scaled by the ATE scale)
  ErrorStats rotation_deg;  // degrees
};
// Relative pose error over pairs delta frames apart in the associated sequence.
RpeResult compute_rpe(const Trajectory& gt, const Trajectory& est, const std::vector<std::pair<size_t, size_t>>& pairs,
                      int delta, double scale);

// Scale drift: how the estimate's scale changes along the run, a diagnostic of monocular maps
// beyond EVALUATION.md's figures. The paired poses are cut into consecutive windows of at least
// window_seconds of ground-truth time; each window's ratio is the estimate's displacement over it
// (chord, first to last pose) against the ground truth's, skipped when the ground truth moved less
// than min_chord metres. The ratios are divided by their mean, and the slope is the least-squares
// line through them over the windows' mid times: negative when the estimate shrinks along the run.
// On slow motion (a hand-held camera moving a few cm a second) the ratios are noisy: read the slope
// with its standard error.
// Needs timestamps (none for an indexed ground truth) and at least 3 windows; else valid is false.
struct ScaleDriftResult {
  bool valid = false;
  double window_seconds = 1.0;
  std::vector<double> times;   // windows' mid times, seconds after the first pair
  std::vector<double> ratios;  // windows' displacement ratios, divided by their mean
  double slope_percent_per_second = 0;
  double slope_se_percent_per_second = 0;  // its standard error, from the ratios' scatter about the line
  double change_percent = 0;   // the slope over the span of the windows' mid times
};
ScaleDriftResult compute_scale_drift(const Trajectory& gt, const Trajectory& est,
                                     const std::vector<std::pair<size_t, size_t>>& pairs, double window_seconds = 1.0,
                                     double min_chord = 0.05);

// The median of the gaps between consecutive timestamps (0 with fewer than two): a sequence's frame period.
double median_gap(const std::vector<double>& timestamps);

// Tracking rate (%): the share of the sequence's duration covered by frames with an estimated pose.
// Each ground-truth sample stands for the time up to the next one; it counts as tracked when an
// estimate lies within max(max_dt, half the estimate's median frame period) of it (so a 100 Hz
// ground truth is fully covered by a 30 Hz estimate); indexed trajectories compare frame indices.
double tracking_rate(const Trajectory& gt, const Trajectory& est, const AssociationOptions& options);

}  // namespace wardmap::slam::eval
