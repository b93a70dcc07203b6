#include "slam/front/rgbd_points.h"

#include <algorithm>

#include "slam/front/submap.h"

namespace wardmap::slam {

Eigen::Vector3d unproject_keypoint(const FrameFeatures& f, size_t i, const SE3& T_wc, const PinholeCamera& c) {
  const double d = f.depth[i];
  const Eigen::Vector3d pc((f.points[i].x() - c.cx) / c.fx * d, (f.points[i].y() - c.cy) / c.fy * d, d);
  return T_wc * pc;
}

std::vector<std::pair<int, std::shared_ptr<MapPoint>>> create_depth_points(const std::shared_ptr<KeyFrame>& kf,
                                                                           Submap& submap, const PinholeCamera& camera,
                                                                           const TrackingOptions& options,
                                                                           bool every_depth) {
  const FrameFeatures& f = kf->features();
  std::vector<std::pair<float, int>> by_depth;
  for (size_t i = 0; i < f.size(); ++i)
    if (f.depth[i] > 0) by_depth.emplace_back(f.depth[i], static_cast<int>(i));
  std::sort(by_depth.begin(), by_depth.end());
  std::vector<std::pair<int, std::shared_ptr<MapPoint>>> created;
  int considered = 0;
  for (const auto& [d, i] : by_depth) {
    if (!every_depth && d > options.close_depth && considered > options.min_depth_points) break;
    ++considered;
    const size_t s = static_cast<size_t>(i);
    const auto& existing = kf->map_point(s);
    if (existing && !existing->bad() && existing->num_observations() > 0) continue;
    auto mp = submap.create_map_point(unproject_keypoint(f, s, kf->pose_wc(), camera), *kf);
    mp->add_observation(kf, i);
    kf->set_map_point(s, mp);
    mp->set_descriptor(f.descriptors.ptr<uchar>(static_cast<int>(i)));
    mp->update_normal_and_depth();
    created.emplace_back(i, mp);
  }
  return created;
}

}  // namespace wardmap::slam
