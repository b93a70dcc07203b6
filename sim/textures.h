// Procedural textures (cv::Mat CV_8UC3, BGR, power-of-two sides) with their own box-filtered
// mip-map pyramid. Generators take a seeded Rng so the same seed gives the same texels everywhere.
#pragma once

#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "sim/rng.h"

namespace wardmap::sim {

struct Texture {
  std::vector<cv::Mat> levels;  // level 0 full size, each next level half as wide and high
  bool wrap = true;             // repeat (tiling surfaces) or clamp (posters, object faces)
};

// Build the pyramid (2x2 integer box filter, rounding half up) down to a side of 4 texels.
// The sides of `level0` must be powers of two.
Texture make_texture(const cv::Mat& level0, bool wrap);

// Surfaces of the building. Periods are what one texture repeat covers in metres.
constexpr double kFloorTilesPeriod = 4.8;  // 8 x 8 tiles of 0.6 m
constexpr double kLinoPeriod = 2.0;
constexpr double kWallPeriod = 2.0;     // along the wall; vertically the texture spans floor to ceiling
constexpr double kCeilingPeriod = 2.4;  // 4 x 4 panels of 0.6 m, one light panel

cv::Mat floor_tiles_texture(Rng& rng);
cv::Mat lino_texture(Rng& rng);
cv::Mat plain_floor_texture(Rng& rng);
// kind: paint | speckle | plain | tiles | wood; base_bgr is the paint colour.
cv::Mat wall_texture(Rng& rng, const std::string& kind, const cv::Scalar& base_bgr, double ceiling_height);
cv::Mat ceiling_texture(Rng& rng);

// Wall decorations.
cv::Mat poster_texture(Rng& rng, int width, int height);
cv::Mat sign_texture(Rng& rng, const std::string& text, const cv::Scalar& bg, const cv::Scalar& fg);

// Materials of objects and fittings.
cv::Mat wood_texture(Rng& rng, const cv::Scalar& base_bgr, int width, int height, bool vertical_grain);
cv::Mat fabric_texture(Rng& rng, const cv::Scalar& base_bgr);
cv::Mat metal_texture(Rng& rng, const cv::Scalar& base_bgr);
cv::Mat solid_texture(const cv::Scalar& bgr);
cv::Mat door_texture(Rng& rng, int variant, const std::string& number);
cv::Mat cabinet_front_texture(Rng& rng, int variant);
cv::Mat sheet_texture(Rng& rng, const cv::Scalar& base_bgr);

}  // namespace wardmap::sim
