// Z-buffered triangle rasteriser on the CPU, deferred: pass 1 resolves visibility per pixel
// (1/z buffer, near-plane clipping, back-face culling), pass 2 shades each pixel once with
// perspective-correct, mip-mapped bilinear texture sampling and flat lighting with distance falloff.
// Pixel (u, v) samples the ray through the pinhole projection point (u, v) (OpenCV convention:
// pixel centres at integer coordinates). Single-threaded and deterministic.
#pragma once

#include <opencv2/core.hpp>
#include <vector>

#include "sim/scene.h"
#include "slam/core/camera.h"
#include "slam/core/se3.h"

namespace wardmap::sim {

struct RenderOptions {
  double near_plane = 0.05;   // metres
  double falloff = 0.006;     // brightness = shade / (1 + falloff * z^2)
  bool triangle_ids = false;  // also fill RenderBuffers::triangle
};

struct RenderBuffers {
  cv::Mat rgb;       // CV_8UC3, BGR (as cv::imwrite expects)
  cv::Mat depth;     // CV_32F, metres along the optical axis, 0 where nothing was hit
  cv::Mat instance;  // CV_32S, object id, 0 = building / background
  cv::Mat triangle;  // CV_32S, index into Scene::triangles, -1 = none (only with triangle_ids)
};

class Rasterizer {
 public:
  // The camera's distortion is ignored (rendering is ideal pinhole).
  Rasterizer(const Scene& scene, const slam::PinholeCamera& camera, RenderOptions options = {});

  // Render everything seen from the camera pose T_wc (camera to world).
  void render(const slam::SE3& T_wc, RenderBuffers& out);
  // Colour only (for motion-blur sub-frames): out is CV_8UC3.
  void render_colour(const slam::SE3& T_wc, cv::Mat& out);
  // Pixels the object covers when drawn alone (no occluders), counted over the image extended by
  // margin_x / margin_y pixels on each side; same coverage rule as render().
  long object_coverage(const slam::SE3& T_wc, int object_id, int margin_x, int margin_y);

  const slam::PinholeCamera& camera() const { return camera_; }

 private:
  struct Item {                  // a clipped, projected triangle with its attribute planes over the image
    double ea[3], eb[3], ec[3];  // edge functions e = ea*x + eb*y + ec, inside where all >= 0
    double aw, bw, cw;           // plane of 1/z
    double au, bu, cu;           // plane of u/z (u in level-0 texels)
    double av, bv, cv;           // plane of v/z
    double minx, maxx, miny, maxy;
    double zmin;
    int tri;
  };
  struct TexLevel {
    const uint8_t* data;
    int width, height, step;
    float scale;  // level-0 texel coordinate to this level's
  };
  struct TexInfo {
    std::vector<TexLevel> levels;
    bool wrap;
  };

  // Transform, cull, clip and set up triangles [first, first + count) for the current limits.
  void prepare(const slam::SE3& T_wc, int first, int count, bool cull);
  void visibility_pass();
  void shade_pass(cv::Mat& rgb);

  const Scene& scene_;
  slam::PinholeCamera camera_;
  RenderOptions options_;
  std::vector<TexInfo> textures_;
  std::vector<Item> items_;
  std::vector<int> order_;
  std::vector<float> zbuf_;  // 1/z, 0 = empty
  std::vector<int> ibuf_;    // item index, -1 = empty
  std::vector<uint32_t> stamp_;
  uint32_t stamp_value_ = 0;
  int lim_x0_ = 0, lim_y0_ = 0, lim_x1_ = 0, lim_y1_ = 0;  // pixel range drawn (inclusive)
};

}  // namespace wardmap::sim
