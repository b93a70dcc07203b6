#include "sim/annotations.h"

#include <algorithm>

namespace wardmap::sim {

std::vector<Annotation> annotate(const Scene& scene, const cv::Mat& instance, Rasterizer& rasterizer,
                                 const slam::SE3& T_wc) {
  const size_t n = scene.objects.size();
  std::vector<long> count(n + 1, 0);
  std::vector<int> x0(n + 1, instance.cols), y0(n + 1, instance.rows), x1(n + 1, -1), y1(n + 1, -1);
  for (int y = 0; y < instance.rows; ++y) {
    const int* row = instance.ptr<int>(y);
    for (int x = 0; x < instance.cols; ++x) {
      const int id = row[x];
      if (id <= 0 || static_cast<size_t>(id) > n) continue;
      ++count[static_cast<size_t>(id)];
      x0[static_cast<size_t>(id)] = std::min(x0[static_cast<size_t>(id)], x);
      x1[static_cast<size_t>(id)] = std::max(x1[static_cast<size_t>(id)], x);
      y0[static_cast<size_t>(id)] = std::min(y0[static_cast<size_t>(id)], y);
      y1[static_cast<size_t>(id)] = std::max(y1[static_cast<size_t>(id)], y);
    }
  }
  std::vector<Annotation> out;
  for (size_t id = 1; id <= n; ++id) {
    if (count[id] == 0) continue;
    Annotation a;
    a.id = static_cast<int>(id);
    a.cls = scene.object(a.id).cls;
    a.box[0] = x0[id];
    a.box[1] = y0[id];
    a.box[2] = x1[id] + 1;
    a.box[3] = y1[id] + 1;
    a.pixels = count[id];
    a.area = rasterizer.object_coverage(T_wc, a.id, instance.cols / 2, instance.rows / 2);
    a.visible = a.area > 0 ? std::min(1.0, static_cast<double>(a.pixels) / static_cast<double>(a.area)) : 0.0;
    out.push_back(a);
  }
  return out;
}

}  // namespace wardmap::sim
