// Pose-only optimisation of a frame against fixed map points (ORB-SLAM's PoseOptimization): a few
// rounds of Levenberg-Marquardt, each followed by a chi2 test on every observation; outliers are
// left out of the next round (and may come back), the Huber loss is used in the first rounds only.
// The default solver is Ceres, given each round's observations as one residual block (each
// observation keeps its own Huber loss; the steps are those of one block per observation, to
// rounding, and the solve is about twice as fast: Ceres's per-block bookkeeping dominated a problem
// of a few hundred 2-row blocks). A small Levenberg-Marquardt written for the 6 pose parameters
// (normal equations accumulated in a 6x6 matrix, relinearised at every accepted step, Ceres's
// trust-region schedule) solves the same problem faster still (PoseSolver::kLevenbergMarquardt).
#pragma once

#include <vector>

#include "slam/core/camera.h"
#include "slam/core/se3.h"

namespace wardmap::slam {

struct PoseObservation {
  Eigen::Vector3d point;   // world
  Eigen::Vector2d pixel;   // undistorted pixel
  double right_u = -1;     // virtual stereo coordinate (RGB-D); < 0 = none
  double inv_sigma = 1.0;  // 1 / (level scale)
};

enum class PoseSolver { kLevenbergMarquardt, kCeres };

struct PoseOptimizerOptions {
  PoseSolver solver = PoseSolver::kCeres;
  int rounds = 4;
  int iterations = 10;    // solver iterations per round (accepted and rejected steps)
  int robust_rounds = 2;  // rounds using the Huber loss
  double chi2_mono = 5.991;
  double chi2_stereo = 7.815;
};

struct PoseEstimate {
  SE3 T_cw;
  std::vector<char> inlier;
  int inliers = 0;
};

PoseEstimate optimize_pose(const SE3& initial_T_cw, const std::vector<PoseObservation>& observations,
                           const PinholeCamera& camera, double bf, const PoseOptimizerOptions& options);

// Squared, whitened reprojection error of one observation (chi2 with 2 or 3 dof); infinity behind the camera.
double observation_chi2(const SE3& T_cw, const PoseObservation& o, const PinholeCamera& camera, double bf);

}  // namespace wardmap::slam
