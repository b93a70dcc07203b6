// Monocular two-view initialisation (ORB-SLAM's scheme, Mur-Artal et al. 2015, Section IV): a
// homography and a fundamental matrix are estimated in parallel by RANSAC on the same minimal sets,
// each scored by its symmetric transfer error; the homography is chosen when its share of the score
// is high (planar or low-parallax scenes), and the chosen model is decomposed into the candidate
// motions, each checked by triangulating the inliers (in front of both cameras, reprojection error,
// parallax). The motion wins only when it clearly beats the others.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <optional>
#include <utility>
#include <vector>

#include "slam/core/camera.h"
#include "slam/core/se3.h"

namespace wardmap::slam {

struct TwoViewOptions {
  int ransac_iterations = 200;     // tracking.init_ransac_iterations
  double sigma = 1.0;              // tracking.init_sigma (px): keypoint noise at level 0
  double homography_share = 0.45;  // tracking.init_homography_share: S_H / (S_H + S_F) above which H is used
  double min_parallax_deg = 1.0;   // tracking.init_min_parallax_deg
  int min_triangulated = 50;       // tracking.init_min_triangulated
  double min_good_ratio = 0.9;     // tracking.init_min_good_ratio: triangulated / model inliers
  double ambiguity_ratio = 0.7;    // tracking.init_ambiguity_ratio: a second motion this good rejects
  std::uint64_t seed = 0;          // RANSAC sampling seed (deterministic)
};

struct TwoViewReconstruction {
  SE3 T_21;                             // camera 1 to camera 2 (|t| = 1)
  std::vector<Eigen::Vector3d> points;  // per match, in camera 1's frame
  std::vector<char> triangulated;       // per match: a good point
  int good = 0;
  double parallax_deg = 0;
  bool homography = false;              // which model was used
  double homography_share = 0;          // S_H / (S_H + S_F)
};

// Homography x2 ~ H x1 from >= 4 pixel pairs (normalised DLT).
Eigen::Matrix3d homography_dlt(const std::vector<Eigen::Vector2d>& p1, const std::vector<Eigen::Vector2d>& p2);
// Fundamental matrix x2' F x1 = 0 from >= 8 pixel pairs (normalised 8-point, rank 2 enforced).
Eigen::Matrix3d fundamental_8point(const std::vector<Eigen::Vector2d>& p1, const std::vector<Eigen::Vector2d>& p2);

// ORB-SLAM's model scores: sum over pairs of (threshold - chi2) of each inlying transfer error.
double score_homography(const Eigen::Matrix3d& H21, const std::vector<Eigen::Vector2d>& p1,
                        const std::vector<Eigen::Vector2d>& p2, double sigma, std::vector<char>& inliers);
double score_fundamental(const Eigen::Matrix3d& F21, const std::vector<Eigen::Vector2d>& p1,
                         const std::vector<Eigen::Vector2d>& p2, double sigma, std::vector<char>& inliers);

// p1[i] <-> p2[i] are undistorted pixels of matched keypoints. Empty when neither model gives one
// clear, well-conditioned motion (then try a later frame).
std::optional<TwoViewReconstruction> reconstruct_two_views(const std::vector<Eigen::Vector2d>& p1,
                                                           const std::vector<Eigen::Vector2d>& p2,
                                                           const PinholeCamera& camera, const TwoViewOptions& options);

}  // namespace wardmap::slam
