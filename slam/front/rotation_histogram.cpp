#include "slam/front/rotation_histogram.h"

#include <cmath>

namespace wardmap::slam {

void RotationHistogram::add(float angle1, float angle2, int match) {
  float rot = angle1 - angle2;
  if (rot < 0) rot += 360.f;
  if (rot >= 360.f) rot -= 360.f;
  size_t bin = static_cast<size_t>(std::lround(rot * bins_.size() / 360.f));
  if (bin >= bins_.size()) bin = 0;
  bins_[bin].push_back(match);
}

std::vector<int> RotationHistogram::rejected() const {
  size_t m[3] = {0, 0, 0};
  int best[3] = {-1, -1, -1};
  for (size_t i = 0; i < bins_.size(); ++i) {
    const size_t s = bins_[i].size();
    if (s > m[0]) {
      m[2] = m[1];
      best[2] = best[1];
      m[1] = m[0];
      best[1] = best[0];
      m[0] = s;
      best[0] = static_cast<int>(i);
    } else if (s > m[1]) {
      m[2] = m[1];
      best[2] = best[1];
      m[1] = s;
      best[1] = static_cast<int>(i);
    } else if (s > m[2]) {
      m[2] = s;
      best[2] = static_cast<int>(i);
    }
  }
  if (m[1] < 0.1 * m[0])
    best[1] = best[2] = -1;
  else if (m[2] < 0.1 * m[0])
    best[2] = -1;
  std::vector<int> out;
  for (size_t i = 0; i < bins_.size(); ++i) {
    const int bi = static_cast<int>(i);
    if (bi == best[0] || bi == best[1] || bi == best[2]) continue;
    out.insert(out.end(), bins_[i].begin(), bins_[i].end());
  }
  return out;
}

}  // namespace wardmap::slam
