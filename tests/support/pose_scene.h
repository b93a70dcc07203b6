// Observations for the pose-only optimisation, shared by its unit tests and its benchmark: random
// points 1.5-6 m in front of a camera at `truth`, seen with 0.5 px noise, every tenth one an
// outlier (25, -30) px off. Header-only: the benchmark harness includes it without GoogleTest.
#pragma once

#include <cmath>
#include <random>
#include <vector>

#include "slam/core/camera.h"
#include "slam/core/se3.h"
#include "slam/front/pose_optimizer.h"

namespace wardmap::test {

struct PoseScene {
  std::vector<slam::PoseObservation> obs;
  std::vector<bool> is_outlier;
};

// With `pyramid_levels`, each observation gets the weight of a random pyramid level (1 / 1.2^l,
// l in 0-7), as the tracker's do; otherwise weight 1.
inline PoseScene make_pose_scene(const slam::PinholeCamera& cam, double bf, const slam::SE3& truth, bool stereo,
                                 int n = 300, unsigned seed = 42, bool pyramid_levels = false) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> ux(-2, 2), uy(-1.5, 1.5), uz(1.5, 6);
  std::normal_distribution<double> noise(0, 0.5);
  std::uniform_int_distribution<int> level(0, 7);
  PoseScene scene;
  while (static_cast<int>(scene.obs.size()) < n) {
    const Eigen::Vector3d pc(ux(rng), uy(rng), uz(rng));
    const Eigen::Vector2d px(cam.fx * pc.x() / pc.z() + cam.cx, cam.fy * pc.y() / pc.z() + cam.cy);
    if (!cam.in_image(px)) continue;
    slam::PoseObservation o;
    o.point = truth.inverse() * pc;
    const bool outlier = scene.obs.size() % 10 == 0;
    o.pixel =
        px + Eigen::Vector2d(noise(rng), noise(rng)) + (outlier ? Eigen::Vector2d(25, -30) : Eigen::Vector2d::Zero());
    if (stereo) o.right_u = px.x() - bf / pc.z() + noise(rng);
    o.inv_sigma = pyramid_levels ? 1.0 / std::pow(1.2, level(rng)) : 1.0;
    scene.obs.push_back(o);
    scene.is_outlier.push_back(outlier);
  }
  return scene;
}

}  // namespace wardmap::test
