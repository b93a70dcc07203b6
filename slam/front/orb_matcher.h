// ORB matching: by projection of map points into a frame (search window scaled by the keypoint
// level, Hamming threshold, ratio test, rotation-consistency histogram), brute-force k-NN for
// bootstrapping against a keyframe, epipolar-constrained search for triangulation, and fusion of
// duplicated points. Keypoint positions are undistorted pixels, so projection is a plain pinhole.
#pragma once

#include <memory>
#include <utility>
#include <vector>

#include "slam/core/camera.h"
#include "slam/front/frame.h"
#include "slam/front/front_options.h"
#include "slam/front/key_frame.h"

namespace wardmap::slam {

class Submap;

// Undistorted pixel of a camera-frame point.
inline Eigen::Vector2d project_pinhole(const PinholeCamera& c, const Eigen::Vector3d& p) {
  return {c.fx * p.x() / p.z() + c.cx, c.fy * p.y() / p.z() + c.cy};
}

// A map point predicted to be in view of a frame (see local_map.h).
struct ProjectionCandidate {
  std::shared_ptr<MapPoint> point;
  Eigen::Vector2d pixel;  // predicted undistorted pixel
  double right_u = -1;    // predicted virtual-stereo u (RGB-D)
  int level = 0;          // predicted pyramid level
  double view_cos = 1;    // cosine between the viewing ray and the point's mean normal
};

class OrbMatcher {
 public:
  OrbMatcher(const MatcherOptions& options, const PinholeCamera& camera) : o_(options), camera_(camera) {}

  // The last frame's matched points projected with current's pose; window `radius` x level scale.
  int search_by_projection(Frame& current, const Frame& last, double radius) const;
  // Local-map candidates not yet matched in `current`; window radius x viewing factor x level scale.
  int search_by_projection(Frame& current, const std::vector<ProjectionCandidate>& candidates, double radius) const;
  // Brute-force 2-NN between the keyframe's points and all frame features (ratio + rotation check).
  int search_by_knn(const KeyFrame& keyframe, Frame& frame) const;
  // Monocular initialisation: each level-0/1 keypoint of f1 matched to f2's keypoints within `window` px
  // of `prior[i]` (where it was found last time; f1's position at first) and `level_span` levels of its
  // own, distance <= th_low, ratio `ratio` when the two nearest are on one level, rotation check.
  // Returns f2's index per f1 keypoint (-1: none); updates prior.
  std::vector<int> search_for_initialisation(const FrameFeatures& f1, const FrameFeatures& f2,
                                             std::vector<Eigen::Vector2d>& prior, double window, double ratio,
                                             int level_span = 0) const;
  // Pairs (i1, i2) of unmatched keypoints of two keyframes satisfying the epipolar constraint (among
  // the keypoints under the same vocabulary node when both keyframes have a direct index).
  std::vector<std::pair<int, int>> search_for_triangulation(const KeyFrame& kf1, const KeyFrame& kf2) const;
  // Projects `points` into `kf`; merges each with the point already there or adds the observation.
  // `chi2` gates the reprojection error. Returns the number of fused points.
  int fuse(const std::shared_ptr<KeyFrame>& kf, const std::vector<std::shared_ptr<MapPoint>>& points, double radius,
           double chi2_mono, double chi2_stereo, Submap& submap) const;

 private:
  MatcherOptions o_;
  PinholeCamera camera_;
};

}  // namespace wardmap::slam
