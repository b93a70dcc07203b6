// Per-frame object annotations from the instance buffer.
#pragma once

#include <opencv2/core.hpp>
#include <vector>

#include "sim/rasterizer.h"
#include "sim/scene.h"

namespace wardmap::sim {

struct Annotation {
  int id = 0;
  ObjectClass cls = ObjectClass::kChair;
  // Pixel box of the visible part, cv::Rect convention: x0, y0 = first covered column / row,
  // x1, y1 = one past the last (so a pixel (i, j) spans [i, i+1) x [j, j+1)).
  int box[4] = {0, 0, 0, 0};
  long pixels = 0;       // visible pixels
  long area = 0;         // pixels of the object drawn alone over the image extended by half its size each side
  double visible = 0.0;  // pixels / area (occlusion and truncation both lower it)
};

// Every object with at least one visible pixel, in id order. Uses the rasteriser to draw each such
// object alone (so call it after the frame's buffers have been taken).
std::vector<Annotation> annotate(const Scene& scene, const cv::Mat& instance, Rasterizer& rasterizer,
                                 const slam::SE3& T_wc);

}  // namespace wardmap::sim
