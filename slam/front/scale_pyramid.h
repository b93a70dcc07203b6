// Scale factors of an ORB image pyramid: level l is the image shrunk by scale_factor^l. The
// keypoint position uncertainty grows with the level (sigma^2 = scale^2l), as in ORB-SLAM.
#pragma once

#include <cmath>
#include <vector>

namespace wardmap::slam {

struct ScalePyramid {
  double scale_factor = 1.2;
  std::vector<double> scale;       // scale_factor^l
  std::vector<double> inv_scale;   // 1 / scale
  std::vector<double> sigma2;      // scale^2
  std::vector<double> inv_sigma2;  // 1 / sigma2

  ScalePyramid() = default;
  ScalePyramid(double factor, int levels) : scale_factor(factor) {
    for (int l = 0; l < levels; ++l) {
      const double s = std::pow(factor, l);
      scale.push_back(s);
      inv_scale.push_back(1.0 / s);
      sigma2.push_back(s * s);
      inv_sigma2.push_back(1.0 / (s * s));
    }
  }
  int levels() const { return static_cast<int>(scale.size()); }
  // The level at which a point seen at `distance` would appear, given it was measured at
  // `max_distance` (its distance at level 0 times the top scale). Clamped to [0, levels-1].
  int predict_level(double distance, double max_distance) const {
    if (distance <= 0) return 0;
    const int l = static_cast<int>(std::ceil(std::log(max_distance / distance) / std::log(scale_factor)));
    return l < 0 ? 0 : (l >= levels() ? levels() - 1 : l);
  }
};

}  // namespace wardmap::slam
