#include "slam/front/orb_matcher.h"

#include <algorithm>
#include <climits>
#include <opencv2/features2d.hpp>

#include "slam/front/descriptor_distance.h"
#include "slam/front/rotation_histogram.h"
#include "slam/front/submap.h"

namespace wardmap::slam {

namespace {

// Undoes the matches the rotation histogram rejects; `slots` maps a match id to its keypoint index.
template <typename Undo>
int apply_rotation_check(const RotationHistogram& hist, int matches, Undo undo) {
  for (int id : hist.rejected()) {
    undo(id);
    --matches;
  }
  return matches;
}

struct Best {
  int dist = INT_MAX, dist2 = INT_MAX, idx = -1, level = -1, level2 = -1;
  void offer(int d, int i, int level_i) {
    if (d < dist) {
      dist2 = dist;
      level2 = level;
      dist = d;
      idx = i;
      level = level_i;
    } else if (d < dist2) {
      dist2 = d;
      level2 = level_i;
    }
  }
};

}  // namespace

int OrbMatcher::search_by_projection(Frame& current, const Frame& last, double radius) const {
  const FrameFeatures& cf = current.features();
  const FrameFeatures& lf = last.features();
  const SE3& T_cw = current.pose_cw();
  RotationHistogram hist(o_.histogram_bins);
  int matches = 0;
  std::vector<int> idx;  // reused by every query
  for (size_t i = 0; i < last.map_points.size(); ++i) {
    const auto& mp = last.map_points[i];
    if (!mp || mp->bad() || last.outlier[i]) continue;
    const Eigen::Vector3d pc = T_cw * mp->position();
    if (pc.z() <= 0) continue;
    const Eigen::Vector2d uv = project_pinhole(camera_, pc);
    if (!camera_.in_image(uv)) continue;
    const int level = lf.levels[i];
    const double r = radius * cf.pyramid->scale[static_cast<size_t>(level)];
    cf.grid.in_area(uv.x(), uv.y(), r, std::max(0, level - 1), level + 1, idx);
    if (idx.empty()) continue;
    const uchar* d = mp->descriptor() ? mp->descriptor() : lf.descriptor(i);
    const double ur = uv.x() - cf.bf / pc.z();
    Best best;
    for (int j : idx) {
      const auto& other = current.map_points[static_cast<size_t>(j)];
      if (other && !other->bad() && other->num_observations() > 0) continue;
      if (cf.right_u[static_cast<size_t>(j)] >= 0 && std::abs(ur - cf.right_u[static_cast<size_t>(j)]) > r) continue;
      best.offer(descriptor_distance(d, cf.descriptor(static_cast<size_t>(j))), j, cf.levels[static_cast<size_t>(j)]);
    }
    if (!descriptor_matches(best.dist, o_.th_high)) continue;
    current.map_points[static_cast<size_t>(best.idx)] = mp;
    current.outlier[static_cast<size_t>(best.idx)] = 0;
    ++matches;
    if (o_.check_orientation)
      hist.add(lf.keypoints[i].angle, cf.keypoints[static_cast<size_t>(best.idx)].angle, best.idx);
  }
  if (o_.check_orientation)
    matches = apply_rotation_check(hist, matches, [&](int j) { current.map_points[static_cast<size_t>(j)].reset(); });
  return matches;
}

int OrbMatcher::search_by_projection(Frame& current, const std::vector<ProjectionCandidate>& candidates,
                                     double radius) const {
  const FrameFeatures& cf = current.features();
  int matches = 0;
  std::vector<int> idx;  // reused by every query
  for (const ProjectionCandidate& c : candidates) {
    const MapPoint& mp = *c.point;
    if (mp.bad() || mp.track_frame_id == current.id()) continue;
    const double view_factor = c.view_cos > 0.998 ? 2.5 : 4.0;
    const double r = radius * view_factor * cf.pyramid->scale[static_cast<size_t>(c.level)];
    cf.grid.in_area(c.pixel.x(), c.pixel.y(), r, c.level - 1, c.level, idx);
    if (idx.empty()) continue;
    const uchar* d = mp.descriptor();
    Best best;
    for (int j : idx) {
      const size_t js = static_cast<size_t>(j);
      const auto& other = current.map_points[js];
      if (other && !other->bad() && other->num_observations() > 0) continue;
      if (c.right_u >= 0 && cf.right_u[js] >= 0 && std::abs(c.right_u - cf.right_u[js]) > r) continue;
      best.offer(descriptor_distance(d, cf.descriptor(js)), j, cf.levels[js]);
    }
    if (!descriptor_matches(best.dist, o_.th_high)) continue;
    if (best.level == best.level2 && best.dist > o_.ratio_projection * best.dist2) continue;
    current.map_points[static_cast<size_t>(best.idx)] = c.point;
    current.outlier[static_cast<size_t>(best.idx)] = 0;
    ++matches;
  }
  return matches;
}

int OrbMatcher::search_by_knn(const KeyFrame& keyframe, Frame& frame) const {
  const FrameFeatures& kf = keyframe.features();
  const FrameFeatures& ff = frame.features();
  std::vector<int> rows;
  for (size_t i = 0; i < keyframe.size(); ++i)
    if (keyframe.map_point(i) && !keyframe.map_point(i)->bad()) rows.push_back(static_cast<int>(i));
  if (rows.empty() || ff.descriptors.empty()) return 0;
  cv::Mat query(static_cast<int>(rows.size()), kDescriptorBytes, CV_8U);
  for (size_t r = 0; r < rows.size(); ++r) kf.descriptors.row(rows[r]).copyTo(query.row(static_cast<int>(r)));
  cv::BFMatcher bf(cv::NORM_HAMMING);
  std::vector<std::vector<cv::DMatch>> knn;
  bf.knnMatch(query, ff.descriptors, knn, 2);

  // Keep, per frame keypoint, the best keyframe match.
  std::vector<int> best_dist(frame.size(), INT_MAX), best_row(frame.size(), -1);
  for (const auto& m : knn) {
    if (m.empty()) continue;
    const int d = static_cast<int>(m[0].distance);
    if (!descriptor_matches(d, o_.th_low)) continue;
    if (m.size() > 1 && d > o_.ratio_knn * m[1].distance) continue;
    const size_t j = static_cast<size_t>(m[0].trainIdx);
    if (d < best_dist[j]) {
      best_dist[j] = d;
      best_row[j] = m[0].queryIdx;
    }
  }
  RotationHistogram hist(o_.histogram_bins);
  int matches = 0;
  for (size_t j = 0; j < frame.size(); ++j) {
    if (best_row[j] < 0) continue;
    const size_t i = static_cast<size_t>(rows[static_cast<size_t>(best_row[j])]);
    frame.map_points[j] = keyframe.map_point(i);
    frame.outlier[j] = 0;
    ++matches;
    if (o_.check_orientation) hist.add(kf.keypoints[i].angle, ff.keypoints[j].angle, static_cast<int>(j));
  }
  if (o_.check_orientation)
    matches = apply_rotation_check(hist, matches, [&](int j) { frame.map_points[static_cast<size_t>(j)].reset(); });
  return matches;
}

std::vector<int> OrbMatcher::search_for_initialisation(const FrameFeatures& f1, const FrameFeatures& f2,
                                                       std::vector<Eigen::Vector2d>& prior, double window, double ratio,
                                                       int level_span) const {
  std::vector<int> m12(f1.size(), -1), m21(f2.size(), -1), dist21(f2.size(), INT_MAX);
  RotationHistogram hist(o_.histogram_bins);
  for (size_t i = 0; i < f1.size(); ++i) {
    const int level = f1.levels[i];
    if (level > 1) continue;  // coarse levels localise too poorly for the two-view geometry
    Best best;
    for (int j :
         f2.grid.in_area(prior[i].x(), prior[i].y(), window, std::max(0, level - level_span), level + level_span))
      best.offer(descriptor_distance(f1.descriptor(i), f2.descriptor(static_cast<size_t>(j))), j,
                 f2.levels[static_cast<size_t>(j)]);
    if (best.idx < 0 || !descriptor_matches(best.dist, o_.th_low)) continue;
    // One corner is often detected on two adjacent levels: the ratio test compares same-level rivals.
    if (best.level == best.level2 && best.dist >= ratio * best.dist2) continue;
    const size_t j = static_cast<size_t>(best.idx);
    if (best.dist >= dist21[j]) continue;
    if (m21[j] >= 0) m12[static_cast<size_t>(m21[j])] = -1;  // a closer f1 keypoint takes it
    m12[i] = best.idx;
    m21[j] = static_cast<int>(i);
    dist21[j] = best.dist;
  }
  if (o_.check_orientation) {
    for (size_t i = 0; i < f1.size(); ++i)
      if (m12[i] >= 0)
        hist.add(f1.keypoints[i].angle, f2.keypoints[static_cast<size_t>(m12[i])].angle, static_cast<int>(i));
    for (int i : hist.rejected()) m12[static_cast<size_t>(i)] = -1;
  }
  for (size_t i = 0; i < f1.size(); ++i)
    if (m12[i] >= 0) prior[i] = f2.points[static_cast<size_t>(m12[i])];
  return m12;
}

std::vector<std::pair<int, int>> OrbMatcher::search_for_triangulation(const KeyFrame& kf1, const KeyFrame& kf2) const {
  const FrameFeatures& f1 = kf1.features();
  const FrameFeatures& f2 = kf2.features();
  // Fundamental matrix between undistorted pixels: x2^T F21 x1 = 0.
  const SE3 T21 = kf2.pose_cw() * kf1.pose_wc();
  Eigen::Matrix3d K;
  K << camera_.fx, 0, camera_.cx, 0, camera_.fy, camera_.cy, 0, 0, 1;
  const Eigen::Matrix3d Kinv = K.inverse();
  const Eigen::Matrix3d F21 = Kinv.transpose() * hat(T21.translation()) * T21.rotation_matrix() * Kinv;
  // Epipole of camera 1 in image 2: points near it give no parallax.
  const Eigen::Vector3d& c1_in_2 = T21.translation();
  const bool epipole_valid = c1_in_2.z() > 1e-9;
  const Eigen::Vector2d epipole = epipole_valid ? project_pinhole(camera_, c1_in_2) : Eigen::Vector2d(-1e9, -1e9);

  std::vector<char> free2(kf2.size(), 0);
  for (size_t j = 0; j < kf2.size(); ++j) free2[j] = !kf2.map_point(j) || kf2.map_point(j)->bad();
  std::vector<int> best_for2(kf2.size(), -1), best_dist2(kf2.size(), INT_MAX);
  RotationHistogram hist(o_.histogram_bins);
  std::vector<int> match12(kf1.size(), -1);
  // Candidates of each keypoint of kf1: kf2's keypoints under the same vocabulary node (ORB-SLAM's
  // bag-of-words guided search) when both keyframes have a direct index, else all of them.
  const bool guided = !kf1.feature_vector.empty() && !kf2.feature_vector.empty();
  std::vector<int> all2;
  if (!guided)
    for (size_t j = 0; j < kf2.size(); ++j) all2.push_back(static_cast<int>(j));
  auto match_one = [&](size_t i, const std::vector<int>& candidates) {
    if (kf1.map_point(i) && !kf1.map_point(i)->bad()) return;
    const Eigen::Vector3d x1(f1.points[i].x(), f1.points[i].y(), 1.0);
    const Eigen::Vector3d line = F21 * x1;
    const double norm2 = line.head<2>().squaredNorm();
    if (norm2 < 1e-12) return;
    Best best;
    for (int j : candidates) {
      const size_t js = static_cast<size_t>(j);
      if (!free2[js]) continue;
      const int d = descriptor_distance(f1.descriptor(i), f2.descriptor(js));
      if (!descriptor_matches(d, o_.th_low) || d > best.dist) continue;
      const Eigen::Vector2d& p2 = f2.points[js];
      const double s2 = f2.pyramid->scale[static_cast<size_t>(f2.levels[js])];
      if (f1.levels[i] == 0 && (p2 - epipole).squaredNorm() < 100 * s2 * s2) continue;
      const double num = line.x() * p2.x() + line.y() * p2.y() + line.z();
      const double dist2 = num * num / norm2;
      if (dist2 > 3.84 * f2.pyramid->sigma2[static_cast<size_t>(f2.levels[js])]) continue;
      best.offer(d, j, f2.levels[js]);
    }
    if (best.idx < 0) return;
    if (best.dist2 != INT_MAX && best.dist > o_.ratio_knn * best.dist2) return;
    const size_t j = static_cast<size_t>(best.idx);
    if (best.dist < best_dist2[j]) {
      if (best_for2[j] >= 0) match12[static_cast<size_t>(best_for2[j])] = -1;
      best_for2[j] = static_cast<int>(i);
      best_dist2[j] = best.dist;
      match12[i] = best.idx;
    }
  };
  if (guided) {
    auto it1 = kf1.feature_vector.begin(), it2 = kf2.feature_vector.begin();
    while (it1 != kf1.feature_vector.end() && it2 != kf2.feature_vector.end()) {
      if (it1->first < it2->first) {
        ++it1;
      } else if (it2->first < it1->first) {
        ++it2;
      } else {
        for (int i : it1->second) match_one(static_cast<size_t>(i), it2->second);
        ++it1;
        ++it2;
      }
    }
  } else {
    for (size_t i = 0; i < kf1.size(); ++i) match_one(i, all2);
  }
  for (size_t i = 0; i < match12.size(); ++i)
    if (match12[i] >= 0 && o_.check_orientation)
      hist.add(f1.keypoints[i].angle, f2.keypoints[static_cast<size_t>(match12[i])].angle, static_cast<int>(i));
  if (o_.check_orientation)
    for (int i : hist.rejected()) match12[static_cast<size_t>(i)] = -1;
  std::vector<std::pair<int, int>> out;
  for (size_t i = 0; i < match12.size(); ++i)
    if (match12[i] >= 0) out.emplace_back(static_cast<int>(i), match12[i]);
  return out;
}

int OrbMatcher::fuse(const std::shared_ptr<KeyFrame>& kf, const std::vector<std::shared_ptr<MapPoint>>& points,
                     double radius, double chi2_mono, double chi2_stereo, Submap& submap) const {
  const FrameFeatures& f = kf->features();
  const SE3& T_cw = kf->pose_cw();
  const Eigen::Vector3d centre = kf->camera_center();
  int fused = 0;
  std::vector<std::shared_ptr<MapPoint>> replaced;
  for (const auto& mp : points) {
    if (!mp || mp->bad() || mp->observed_by(kf->id())) continue;
    const Eigen::Vector3d pc = T_cw * mp->position();
    if (pc.z() <= 0) continue;
    const Eigen::Vector2d uv = project_pinhole(camera_, pc);
    if (!camera_.in_image(uv)) continue;
    const Eigen::Vector3d ray = mp->position() - centre;
    const double dist = ray.norm();
    if (dist < mp->min_distance() || dist > mp->max_distance()) continue;
    if (ray.dot(mp->normal()) < 0.5 * dist) continue;
    const int level = mp->predict_level(dist, *f.pyramid);
    const double r = radius * f.pyramid->scale[static_cast<size_t>(level)];
    const double ur = uv.x() - f.bf / pc.z();
    Best best;
    for (int j : f.grid.in_area(uv.x(), uv.y(), r)) {
      const size_t js = static_cast<size_t>(j);
      const int kl = f.levels[js];
      if (kl < level - 1 || kl > level) continue;
      const double inv_s2 = f.pyramid->inv_sigma2[static_cast<size_t>(kl)];
      double e2 = (f.points[js] - uv).squaredNorm();
      if (f.right_u[js] >= 0) {
        const double er = ur - f.right_u[js];
        if ((e2 + er * er) * inv_s2 > chi2_stereo) continue;
      } else if (e2 * inv_s2 > chi2_mono) {
        continue;
      }
      best.offer(descriptor_distance(mp->descriptor(), f.descriptor(js)), j, kl);
    }
    if (!descriptor_matches(best.dist, o_.th_low)) continue;
    const size_t j = static_cast<size_t>(best.idx);
    const auto& existing = kf->map_point(j);
    if (existing && !existing->bad()) {
      if (existing == mp) continue;
      if (existing->num_observations() > mp->num_observations()) {
        mp->replace_with(existing);
      } else {
        existing->replace_with(mp);
        replaced.push_back(existing);
      }
    } else {
      mp->add_observation(kf, static_cast<int>(j));
      kf->set_map_point(j, mp);
    }
    ++fused;
  }
  submap.purge_bad_points(points);
  submap.purge_bad_points(replaced);
  return fused;
}

}  // namespace wardmap::slam
