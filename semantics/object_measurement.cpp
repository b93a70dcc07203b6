#include "semantics/object_measurement.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <limits>
#include <map>

#include "semantics/object_metrics.h"

namespace wardmap::semantics {

namespace {

double percentile(std::vector<double>& v, double q) {
  const size_t k = static_cast<size_t>(std::clamp(q, 0.0, 1.0) * (v.size() - 1));
  std::nth_element(v.begin(), v.begin() + k, v.end());
  return v[k];
}

// A point of a vertical face: its horizontal unit normal, turned towards the camera, and how
// vertical the face stands (1: upright).
struct FacePoint {
  Eigen::Vector3d p, n;
  double weight;
};

// The points of the object's vertical faces among the given pixels and their world points: the
// surface normal from the depth `step` pixels right and below (none across a depth jump), kept when
// it stands within 17 degrees of horizontal.
std::vector<FacePoint> vertical_face_points(const cv::Mat& depth, const slam::PinholeCamera& cam, const slam::SE3& T_wc,
                                            const std::vector<std::pair<cv::Point, Eigen::Vector3d>>& pixels,
                                            const Eigen::Vector3d& z, int step) {
  const auto point = [&](int x, int y) -> std::optional<Eigen::Vector3d> {
    if (x < 0 || y < 0 || x >= depth.cols || y >= depth.rows) return std::nullopt;
    const double d = depth.at<float>(y, x);
    if (!(d > 0)) return std::nullopt;
    return T_wc * (cam.unproject(Eigen::Vector2d(x, y)) * d);
  };
  std::vector<FacePoint> faces;
  for (const auto& [px, p] : pixels) {
    const auto pr = point(px.x + step, px.y), pd = point(px.x, px.y + step);
    if (!pr || !pd) continue;
    const Eigen::Vector3d a = *pr - p, b = *pd - p;
    const double spacing = (p - T_wc.translation()).norm() * step / cam.fx;
    if (a.norm() > 4 * spacing + 0.05 || b.norm() > 4 * spacing + 0.05) continue;
    Eigen::Vector3d n = a.cross(b);
    if (n.norm() < 1e-12) continue;
    n.normalize();
    const double vertical = std::abs(n.dot(z));
    if (vertical > 0.3) continue;
    n -= n.dot(z) * z;
    n.normalize();
    if (n.dot(T_wc.translation() - p) < 0) n = -n;
    faces.push_back({p, n, 1 - vertical});
  }
  return faces;
}

// The horizontal axis of the object's dominant vertical faces: their normals vote for their
// direction modulo a quarter turn, weighted by how upright the face stands; the fullest 3-degree
// bin, refined by the mean of the votes within 3 degrees of it, is one axis of the object's box.
// Of it and the axis across it, the one along which the points' 5-95 % extent is longer is
// returned. Unlike the principal axes it does not turn with where the points crowd (a near end
// holds more pixels per metre). None with fewer than min_votes face points.
std::optional<Eigen::Vector3d> vertical_face_axis(const std::vector<FacePoint>& faces,
                                                  const std::vector<Eigen::Vector3d>& world, const Eigen::Vector3d& z,
                                                  const Eigen::Vector3d& e1, const Eigen::Vector3d& e2, int min_votes) {
  if (static_cast<int>(faces.size()) < min_votes) return std::nullopt;
  const auto angle_of = [&](const Eigen::Vector3d& n) { return std::fmod(std::atan2(n.dot(e2), n.dot(e1)) + 2 * M_PI, M_PI / 2); };
  constexpr int kBins = 30;  // 3 degrees each
  std::array<double, kBins> hist{};
  for (const FacePoint& f : faces) hist[std::min(kBins - 1, static_cast<int>(angle_of(f.n) / (M_PI / 2) * kBins))] += f.weight;
  const auto around = [&](int i) { return hist[i] + hist[(i + 1) % kBins] + hist[(i + kBins - 1) % kBins]; };
  int best = 0;
  for (int i = 1; i < kBins; ++i)
    if (around(i) > around(best)) best = i;
  const double centre = (best + 0.5) * (M_PI / 2) / kBins;
  double sum = 0, weight = 0;
  for (const FacePoint& f : faces) {
    double d = angle_of(f.n) - centre;  // wrapped to the peak's quarter turn
    if (d > M_PI / 4) d -= M_PI / 2;
    if (d < -M_PI / 4) d += M_PI / 2;
    if (std::abs(d) <= M_PI / 60) sum += f.weight * d, weight += f.weight;
  }
  const double angle = centre + (weight > 0 ? sum / weight : 0);
  const Eigen::Vector3d u = std::cos(angle) * e1 + std::sin(angle) * e2, v = z.cross(u);
  std::vector<double> a, b;
  for (const auto& p : world) a.push_back(p.dot(u)), b.push_back(p.dot(v));
  const double la = percentile(a, 0.95) - percentile(a, 0.05), lb = percentile(b, 0.95) - percentile(b, 0.05);
  return la >= lb ? u : v;
}

// Where along `axis` the object's face across it stands, when the camera sees it: the median
// position of the face points whose normal lies within 10 degrees of the axis (either way; the
// camera sees one of the two faces), with the side the face looks to (+1: +axis). None when fewer
// than min_points.
std::optional<std::pair<double, double>> seen_face(const std::vector<FacePoint>& faces, const Eigen::Vector3d& axis,
                                                   int min_points) {
  std::vector<double> plus, minus;
  for (const FacePoint& f : faces) {
    const double c = f.n.dot(axis);
    if (c > std::cos(M_PI / 18)) plus.push_back(f.p.dot(axis));
    if (c < -std::cos(M_PI / 18)) minus.push_back(f.p.dot(axis));
  }
  auto& side = plus.size() >= minus.size() ? plus : minus;
  if (static_cast<int>(side.size()) < min_points) return std::nullopt;
  return std::make_pair(percentile(side, 0.5), &side == &plus ? 1.0 : -1.0);
}

}  // namespace

Eigen::Vector3d estimate_up(const std::vector<slam::SE3>& poses) {
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  Eigen::Matrix3d rights = Eigen::Matrix3d::Zero();  // sum of x x^T over the cameras' right axes
  Eigen::Vector3d right_sum = Eigen::Vector3d::Zero();
  for (const auto& T : poses) {
    const Eigen::Matrix3d R = T.rotation_matrix();
    sum -= R.col(1);
    rights += R.col(0) * R.col(0).transpose();
    right_sum += R.col(0);
  }
  if (sum.norm() < 1e-9) return Eigen::Vector3d::UnitZ();
  const Eigen::Vector3d mean_up = sum.normalized();
  // A camera looking down (a robot's, or a hand-held one at a table) tilts its -y axis towards its
  // view: the synthetic ward's cameras pitch 11-23 degrees down, and the mean -y axis leaned 12.6
  // degrees, tilting every measured box. Cameras seldom roll, so their right axes are horizontal:
  // once they have turned enough (the right axes spread over a plane), up is the direction
  // orthogonal to all of them, the eigenvector of the smallest eigenvalue of sum(x x^T).
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(rights);
  const double n = static_cast<double>(poses.size());
  constexpr double kMinTurnSpread = 0.02;  // per camera: right axes spread over +-14 degrees of yaw or more
  if (eig.eigenvalues()(1) - eig.eigenvalues()(0) >= kMinTurnSpread * n) {
    const Eigen::Vector3d up = eig.eigenvectors().col(0);
    return up.dot(mean_up) >= 0 ? up : Eigen::Vector3d(-up);
  }
  // Never turned: only the mean right axis is known to be horizontal.
  if (right_sum.norm() < 1e-9) return mean_up;
  const Eigen::Vector3d x = right_sum.normalized();
  const Eigen::Vector3d up = mean_up - mean_up.dot(x) * x;
  return up.norm() < 1e-9 ? mean_up : Eigen::Vector3d(up.normalized());
}

Eigen::Matrix3d upright_rotation(const Eigen::Vector3d& up, const Eigen::Vector3d& axis) {
  const Eigen::Vector3d z = up.normalized();
  Eigen::Vector3d x = axis - axis.dot(z) * z;
  if (x.norm() < 1e-9) x = z.unitOrthogonal();
  x.normalize();
  // A box is symmetric under a half turn: pick the sign deterministically (largest |component| > 0).
  int k;
  x.cwiseAbs().maxCoeff(&k);
  if (x(k) < 0) x = -x;
  Eigen::Matrix3d R;
  R.col(0) = x;
  R.col(1) = z.cross(x);
  R.col(2) = z;
  return R;
}

namespace {

// An occluder ready for the per-pixel test: its image box, and when it has a measured 3-D box, the
// world-to-box transform and the inflated half size.
struct OccluderMask {
  Eigen::Vector4d box;
  bool by_box = true;
  slam::SE3 world_to_box;
  Eigen::Vector3d half_size;
  double far_depth = -1;  // > 0: every pixel of the image box no deeper than this (camera z) is hidden
  bool same_class = false;  // the occluder is of the measured detection's class
  double box_far_depth = -1;  // the deepest corner of its inflated 3-D box (camera z), when measured
  double box_near_depth = -1;  // its nearest corner (camera z), when measured
};

std::vector<OccluderMask> occluder_masks(const std::vector<Occluder>& occluders, double inflate, double support_top_inflate,
                                        const slam::SE3& T_wc, const std::string& far_end, bool box_mask_to_far_end) {
  std::vector<OccluderMask> masks;
  for (const auto& o : occluders) {
    // A box-masked class (a pole, a wheelchair: an open frame) hides its whole image box, or with
    // box_mask_to_far_end and a pose, its image box up to its far end: what stands behind it shows
    // between its spokes and beside its shaft.
    const bool to_far_end = o.pose && (!o.box_masked || box_mask_to_far_end);
    OccluderMask m{o.box, !to_far_end, {}, Eigen::Vector3d::Zero()};
    if (to_far_end) m.world_to_box = o.pose->pose.inverse(), m.half_size = 0.5 * o.pose->size.array() + inflate;
    // A support's top is its measured top surface: what rises just above it (a chair's back behind a
    // table) is not the support's.
    if (to_far_end && o.support) m.half_size(2) = 0.5 * o.pose->size(2) + support_top_inflate;
    m.same_class = o.same_class;
    if (to_far_end) {
      // The deepest corner: the centre's depth plus each half axis's reach along the optical axis.
      const slam::SE3 T_cb = T_wc.inverse() * o.pose->pose;
      const double reach = T_cb.rotation_matrix().row(2).cwiseAbs().dot(m.half_size);
      m.box_far_depth = T_cb.translation().z() + reach;
      m.box_near_depth = T_cb.translation().z() - reach;
    }
    if (to_far_end && (o.box_masked || far_end == "all" || (far_end == "same_class" && o.same_class)))
      m.far_depth = m.box_far_depth;
    masks.push_back(m);
  }
  return masks;
}

// Whether the world point of pixel (x, y) is hidden by one of the occluders; `inside_same_class`,
// when given, tells whether the measured 3-D box of an occluder of the detection's class holds it.
bool hidden_by(const std::vector<OccluderMask>& masks, int x, int y, const Eigen::Vector3d& p_world, double z = -1,
               bool* inside_same_class = nullptr) {
  bool hidden = false;
  for (const auto& m : masks) {
    const auto& b = m.box;
    if (x < b(0) || x > b(2) || y < b(1) || y > b(3)) continue;
    // A mask by box hides its whole box; otherwise a pixel is hidden inside the occluder's measured
    // 3-D box (which also says whether a same-class box holds it) or up to its far depth.
    const bool in_3d_box =
        !m.by_box && ((m.world_to_box * p_world).cwiseAbs().array() <= m.half_size.array()).all();
    if (in_3d_box) {
      hidden = true;
      if (inside_same_class && m.same_class) *inside_same_class = true;
    } else if (m.by_box || (m.far_depth > 0 && z > 0 && z <= m.far_depth)) {
      hidden = true;
    }
    if (hidden && (!inside_same_class || *inside_same_class)) return true;
  }
  return hidden;
}

// Where the ray through a pixel meets the plane through on_plane with the given normal (none when
// the ray runs along the plane or meets it behind the camera).
std::optional<Eigen::Vector3d> ray_meets_plane(const slam::PinholeCamera& cam, const slam::SE3& T_wc,
                                               const Eigen::Vector2d& pixel, const Eigen::Vector3d& on_plane,
                                               const Eigen::Vector3d& normal) {
  const Eigen::Vector3d ray = T_wc.rotation() * cam.unproject(pixel);
  const double facing = ray.dot(normal);
  if (std::abs(facing) < 1e-6) return std::nullopt;
  const double t = (on_plane - T_wc.translation()).dot(normal) / facing;
  if (t <= 0) return std::nullopt;
  return Eigen::Vector3d(T_wc.translation() + t * ray);
}

// The heights (along `up`) of the pixels in rows first..last (clipped to the image), about 40
// columns spread over x0..x1; pixels without depth are skipped.
std::vector<double> pixel_heights(const cv::Mat& depth, const slam::PinholeCamera& cam, const slam::SE3& T_wc,
                                  int first, int last, int x0, int x1, const Eigen::Vector3d& up) {
  std::vector<double> hs;
  const int step = std::max(1, (x1 - x0) / 40);
  for (int y = std::max(0, first); y <= last && y < depth.rows; ++y)
    for (int x = x0; x <= x1; x += step) {
      const double z = depth.at<float>(y, x);
      if (z > 0) hs.push_back((T_wc * (cam.unproject(Eigen::Vector2d(x, y)) * z)).dot(up));
    }
  return hs;
}

// The floor's height (along `up`) just below a box: the median height of the pixels 3-8 rows under
// its bottom edge, columns x0..x1, when they agree within `spread` (their 10-90 % range); none when
// the image ends there or something other than a floor lies there.
std::optional<double> floor_below_box(const cv::Mat& depth, const slam::PinholeCamera& cam, const slam::SE3& T_wc,
                                      const Eigen::Vector4d& box, int x0, int x1, const Eigen::Vector3d& up,
                                      double spread) {
  const int bottom = static_cast<int>(box(3));
  std::vector<double> hs = pixel_heights(depth, cam, T_wc, bottom + 3, bottom + 8, x0, x1, up);
  if (hs.size() < 10) return std::nullopt;
  if (percentile(hs, 0.9) - percentile(hs, 0.1) > spread) return std::nullopt;
  return percentile(hs, 0.5);
}

// The keyframe's floor (along `up`): the median of the floors found just below its boxes that do not
// touch the image's bottom (floor_below_box); none when no box shows one.
std::optional<double> keyframe_floor(const cv::Mat& depth, const slam::PinholeCamera& cam, const slam::SE3& T_wc,
                                     const std::vector<Eigen::Vector4d>& boxes, const Eigen::Vector3d& up,
                                     const MeasurementOptions& o) {
  std::vector<double> floors;
  for (const Eigen::Vector4d& box : boxes) {
    if (box(3) >= depth.rows - 1 - o.border_margin) continue;
    const int x0 = std::max(0, static_cast<int>(std::ceil(box(0)))),
              x1 = std::min(depth.cols - 1, static_cast<int>(box(2)));
    if (const auto f = floor_below_box(depth, cam, T_wc, box, x0, x1, up.normalized(), o.floor_spread))
      floors.push_back(*f);
  }
  if (floors.empty()) return std::nullopt;
  return percentile(floors, 0.5);
}

// Where the pixels of rows first..last (columns x0..x1) that stand higher than `above` along `up`,
// at depths z_near..z_far and not hidden by an occluder, lie along `axis`: the q-quantile of their
// positions, when at least 5 do. They are an object's low parts (a wheelchair's footplate), the
// floor left out.
std::optional<double> low_rows_extent(const cv::Mat& depth, const slam::PinholeCamera& cam, const slam::SE3& T_wc,
                                      const std::vector<OccluderMask>& masks, int first, int last, int x0, int x1,
                                      double z_near, double z_far, const Eigen::Vector3d& up, double above,
                                      const Eigen::Vector3d& axis, double q) {
  std::vector<double> along;
  for (int y = std::max(0, first); y <= std::min(last, depth.rows - 1); ++y)
    for (int x = x0; x <= x1; ++x) {
      const double d = depth.at<float>(y, x);
      if (!(d > 0 && d >= z_near && d <= z_far)) continue;
      const Eigen::Vector3d p = T_wc * (cam.unproject(Eigen::Vector2d(x, y)) * d);
      if (p.dot(up) < above || hidden_by(masks, x, y, p, d)) continue;
      along.push_back(p.dot(axis));
    }
  if (along.size() < 5) return std::nullopt;
  return percentile(along, q);
}

// Which image borders the box touches.
struct BorderCut {
  bool left = false, right = false, top = false, bottom = false;
};

// Whether the foot window applies to detections of `label` (on, and a foot_window_classes class).
bool foot_window_applies(const std::string& label, const SemanticOptions& options) {
  return options.measurement.foot_window_rows > 0 && options.foot_window_classes.count(label) > 0;
}

// The depths at which a foot_window_classes object's nearest parts stand: where the ray through its
// box's bottom row (middle column), moved measurement.foot_window_rows of the box's height down and
// up, meets the floor just below the box, foot_window_slack nearer and farther. A box whose lower end
// nearer detections hide (`bottom_hidden`) stands behind the near end of each measured one that
// reaches its bottom row (the keyframe's floor is no bound there: on 7-Scenes it was the table's
// top, under the chairs' backs seen behind the table).
// None when off, for other classes, for boxes cut at a side or reaching within that error of the
// image's bottom, when no floor shows below the box, or when the box is shorter than
// foot_min_height_share of the class's height standing on it.
std::optional<std::pair<double, double>> foot_depths(const cv::Mat& depth, const slam::PinholeCamera& cam,
                                                     const slam::SE3& T_wc, const Eigen::Vector4d& box, int x0, int x1,
                                                     const Eigen::Vector3d& up, const std::string& label,
                                                     const BorderCut& cut, const SemanticOptions& options,
                                                     std::optional<double> keyframe_floor,
                                                     const std::vector<OccluderMask>& masks, bool bottom_hidden) {
  const MeasurementOptions& o = options.measurement;
  if (!foot_window_applies(label, options) || cut.left || cut.right) return std::nullopt;
  const slam::SE3 T_cw = T_wc.inverse();
  const double centre = 0.5 * (box(0) + box(2)), rows = o.foot_window_rows * (box(3) - box(1));
  // A ray at or above the horizon never meets the floor: the foot may then stand at any distance.
  const auto floor_depth = [&](double floor, double row) {
    const auto p = ray_meets_plane(cam, T_wc, Eigen::Vector2d(centre, row), floor * up, up);
    return p ? (T_cw * *p).z() : std::numeric_limits<double>::infinity();
  };
  if (cut.bottom) {
    if (!bottom_hidden || box(3) >= depth.rows - 1 - o.border_margin) return std::nullopt;
    double nearest = 0;
    for (const auto& m : masks)
      if (m.box_near_depth > 0 && m.box(0) <= box(2) && m.box(2) >= box(0) && m.box(1) <= box(3) + 3 &&
          m.box(3) >= box(3) - 2)
        nearest = std::max(nearest, m.box_near_depth);
    if (nearest <= 0) return std::nullopt;
    return std::make_pair(nearest - o.foot_window_slack, std::numeric_limits<double>::infinity());
  }
  // Within the detector's error of the image's bottom, the object's foot may lie below the image.
  if (box(3) + rows + 8 > depth.rows - 1) return std::nullopt;
  auto floor = floor_below_box(depth, cam, T_wc, box, x0, x1, up, o.floor_spread);
  // Something standing in front of the box's lower end (a chair of the row, missed) leaves the floor
  // under part of it: the keyframe's floor, where most of those pixels lie on it.
  if (!floor && keyframe_floor) {
    const int bottom = static_cast<int>(box(3));
    const std::vector<double> hs = pixel_heights(depth, cam, T_wc, bottom + 3, bottom + 8, x0, x1, up);
    const auto on =
        std::count_if(hs.begin(), hs.end(), [&](double h) { return std::abs(h - *keyframe_floor) <= o.floor_spread; });
    if (hs.size() >= 10 && on >= o.foot_floor_share * hs.size()) floor = keyframe_floor;
  }
  if (!floor) return std::nullopt;
  // Standing there, the object rises its class's height: a box much shorter than that is not all of
  // it on that floor (a chair's back seen above a table, whose top is then the "floor" below it).
  const auto size = options.class_sizes.find(label);
  const auto foot = ray_meets_plane(cam, T_wc, Eigen::Vector2d(centre, box(3)), *floor * up, up);
  if (size == options.class_sizes.end() || !foot) return std::nullopt;
  const Eigen::Vector3d foot_c = T_cw * *foot, top_c = T_cw * (*foot + size->second[2] * up);
  if (top_c.z() <= 0 || box(3) - box(1) < o.foot_min_height_share * (cam.project(foot_c).y() - cam.project(top_c).y()))
    return std::nullopt;
  return std::make_pair(floor_depth(*floor, box(3) + rows) - o.foot_window_slack,
                        floor_depth(*floor, box(3) - rows) + o.foot_window_slack);
}

// Whether nearer detections hide the box's lower end over at least `share` of its width (a cabinet
// behind a bed): the visible part then ends at the occluder, not at the object's own end. A column
// counts when the pixel just below the box's bottom edge, or on its last rows (detector boxes are a
// few pixels off), is hidden as the per-pixel occlusion test sees it.
bool bottom_occluded(const cv::Mat& depth, const slam::PinholeCamera& cam, const slam::SE3& T_wc,
                     const Eigen::Vector4d& box, const std::vector<OccluderMask>& masks, double share) {
  if (masks.empty()) return false;
  const int rows[2] = {std::clamp(static_cast<int>(box(3)) + 3, 0, depth.rows - 1),
                       std::clamp(static_cast<int>(box(3)) - 2, 0, depth.rows - 1)};
  const int x0 = std::max(0, static_cast<int>(std::ceil(box(0)))), x1 = std::min(depth.cols - 1, static_cast<int>(box(2)));
  const int step = std::max(1, (x1 - x0) / 40);
  int hidden = 0, total = 0;
  for (int x = x0; x <= x1; x += step, ++total)
    for (int y : rows) {
      const double z = depth.at<float>(y, x);
      if (z > 0 && hidden_by(masks, x, y, T_wc * (cam.unproject(Eigen::Vector2d(x, y)) * z))) {
        ++hidden;
        break;
      }
    }
  return total > 0 && hidden >= share * total;
}

// The height of the horizontal surface that the lowest rows of an object's points show (the bottom
// `band` share of the trimmed rows y0..y1), when they show one rather than a face: over those rows,
// the rows' median heights along `up` vary less than their median horizontal distances from the
// camera (a bed's top seen from above). Fewer than 3 rows, or a face: none.
std::optional<double> bottom_rows_top_height(const std::vector<std::pair<int, Eigen::Vector3d>>& points,
                                             const Eigen::Vector3d& camera, const Eigen::Vector3d& up, int y0, int y1,
                                             double band) {
  const double from = y1 - band * (y1 - y0);
  std::map<int, std::pair<std::vector<double>, std::vector<double>>> rows;  // row -> heights, distances
  for (const auto& [y, p] : points) {
    if (y < from) continue;
    const Eigen::Vector3d d = p - camera;
    rows[y].first.push_back(p.dot(up));
    rows[y].second.push_back((d - d.dot(up) * up).norm());
  }
  if (rows.size() < 3) return std::nullopt;
  std::vector<double> heights;
  double h_lo = 1e9, h_hi = -1e9, d_lo = 1e9, d_hi = -1e9;
  for (auto& [y, r] : rows) {
    const double h = percentile(r.first, 0.5), d = percentile(r.second, 0.5);
    heights.push_back(h);
    h_lo = std::min(h_lo, h), h_hi = std::max(h_hi, h), d_lo = std::min(d_lo, d), d_hi = std::max(d_hi, d);
  }
  if (d_hi - d_lo <= h_hi - h_lo) return std::nullopt;
  return percentile(heights, 0.5);
}

// Whether a surface at `height` (along `up`) fills the image rows from just below the box's bottom
// edge to the image's bottom border (columns x0..x1): the object's top continues past a box that ends
// a few pixels short of the border (detector boxes are a few pixels off), so the border cuts it.
bool surface_reaches_bottom_border(const cv::Mat& depth, const slam::PinholeCamera& cam, const slam::SE3& T_wc,
                                   const Eigen::Vector4d& box, int x0, int x1, const Eigen::Vector3d& up,
                                   double height, double tolerance) {
  const int first = std::max(0, static_cast<int>(std::ceil(box(3))) + 1);
  std::vector<double> hs = pixel_heights(depth, cam, T_wc, first, depth.rows - 1, x0, x1, up);
  if (hs.empty()) return first >= depth.rows;  // no rows below the box: it touches the border
  return std::abs(percentile(hs, 0.5) - height) <= tolerance;
}

// measure_pose_from_depth; with `thin_side_cut_as_uncut`, only for a thin class's box cut at one
// side border, measured as if that border did not cut it (measure_thin_side_cut).
std::optional<ObjectPose> measure_pose(const cv::Mat& depth, const slam::PinholeCamera& cam, const slam::SE3& T_wc,
                                       const Eigen::Vector4d& box, const Eigen::Vector3d& up, const std::string& label,
                                       const SemanticOptions& options, const std::vector<Occluder>& occluders,
                                       bool thin_side_cut_as_uncut, bool* duplicate = nullptr,
                                       std::optional<double> keyframe_floor = std::nullopt) {
  const MeasurementOptions& o = options.measurement;
  if (depth.empty() || depth.type() != CV_32F) return std::nullopt;
  const double w = box(2) - box(0), h = box(3) - box(1);
  // A sliver of a box (a door far down a corridor, seen edge-on) holds too few columns to place it.
  if (w < o.min_box_side || h < o.min_box_side) return std::nullopt;
  const auto class_size = options.class_sizes.find(label);
  const bool sized = class_size != options.class_sizes.end();
  // Cut off by the image border: the visible part's centre is not the object's. A cut at the top or
  // the bottom is completed from the class's height (the opposite end is real; cameras are upright).
  // A cut at the left or right is completed along the seen face to the class's horizontal size that
  // holds what is seen, when only one does (which face is seen is a guess: Eq. 4-6 outvotes a wrong one).
  const double m = o.border_margin;
  BorderCut cut;
  cut.left = box(0) <= m, cut.top = box(1) <= m;
  cut.right = box(2) >= depth.cols - 1 - m, cut.bottom = box(3) >= depth.rows - 1 - m;
  const bool thin = options.thin_classes.count(label) > 0;
  if (thin_side_cut_as_uncut) {
    if (!thin || cut.left == cut.right) return std::nullopt;
    cut.left = cut.right = false;
  }
  // Hidden at the bottom by a nearer detection: completed as a bottom cut is.
  const std::vector<OccluderMask> masks =
      occluder_masks(occluders, o.occluder_inflate, o.support_top_inflate, T_wc, o.mask_to_far_end, o.box_mask_to_far_end);
  const bool bottom_hidden =
      sized && o.occluded_bottom_share <= 1 && bottom_occluded(depth, cam, T_wc, box, masks, o.occluded_bottom_share);
  if (bottom_hidden) cut.bottom = true;
  const bool completes = sized && o.complete_depth_with_class_size;
  const bool side = cut.left || cut.right;
  if ((side && (!completes || !o.complete_side_cuts || thin)) ||
      (cut.left && cut.right) ||
      ((cut.top || cut.bottom) && !completes) || (cut.top && cut.bottom))
    return std::nullopt;
  const int x0 = std::max(0, static_cast<int>(std::floor(box(0) + o.box_shrink * w)));
  const int x1 = std::min(depth.cols - 1, static_cast<int>(std::ceil(box(2) - o.box_shrink * w)));
  const int y0 = std::max(0, static_cast<int>(std::floor(box(1) + o.box_shrink * h)));
  const int y1 = std::min(depth.rows - 1, static_cast<int>(std::ceil(box(3) - o.box_shrink * h)));
  const double area = static_cast<double>(x1 - x0 + 1) * (y1 - y0 + 1);
  const int stride = std::max(1, static_cast<int>(std::sqrt(area / o.target_samples)));
  // A pole's shaft is a few pixels wide: every column is sampled, so that its share of the samples
  // is its share of the box's width rather than how many of the strided columns happen to hit it.
  const bool axis = options.axis_classes.count(label) > 0;
  const int column_stride = axis ? 1 : stride;
  struct Sample {
    double z;           // depth
    Eigen::Vector3d p;  // world point
    int x, y;           // image column and row
  };
  std::vector<Sample> samples;
  int valid = 0, inside_same_class = 0;
  for (int y = y0; y <= y1; y += stride) {
    const float* row = depth.ptr<float>(y);
    for (int x = x0; x <= x1; x += column_stride) {
      const double z = row[x];
      if (!(z >= o.min_depth && z <= o.max_depth)) continue;
      ++valid;
      const Eigen::Vector3d p = T_wc * (cam.unproject(Eigen::Vector2d(x, y)) * z);
      bool inside = false;
      if (hidden_by(masks, x, y, p, z, &inside)) {
        inside_same_class += inside;
        continue;
      }
      samples.push_back({z, p, x, y});
    }
  }
  if (static_cast<int>(samples.size()) < o.min_points) return std::nullopt;
  // The object is the depth window, as deep as the object, that holds the most points: it owns the
  // box (what lies behind it is wall or floor, what lies in front a partial occluder).
  std::sort(samples.begin(), samples.end(), [](const Sample& a, const Sample& b) { return a.z < b.z; });
  double band = o.depth_band;
  if (sized) band = std::max(0.1, std::max(class_size->second[0], class_size->second[1]));
  // Thin objects (a pole) own few of their box's pixels: take the nearest window with enough of them.
  const size_t need = std::max<size_t>(o.min_points, static_cast<size_t>((thin ? o.thin_support : o.cluster_support) *
                                                                          samples.size()));
  // A side cut keeps the box's uncut end: the window must hold the depth of the columns there (an
  // oblique door's nearest part would otherwise win, and its real end be lost).
  const int edge_width = std::max(stride, static_cast<int>(0.15 * (x1 - x0)));
  const auto at_uncut_edge = [&](const Sample& p) { return cut.left ? p.x >= x1 - edge_width : p.x <= x0 + edge_width; };
  double edge_depth = -1;
  if (side && !thin) {
    std::vector<double> zs;
    for (const Sample& p : samples)
      if (at_uncut_edge(p)) zs.push_back(p.z);
    if (zs.empty()) return std::nullopt;
    edge_depth = percentile(zs, 0.5);
  }
  // An axis class (a pole) rises above the furniture in front of it (a bed's footboard, a chair):
  // its window starts at a point of the box's upper half, which shows its shaft.
  const int mid_row = (y0 + y1) / 2;
  const auto foot = foot_depths(depth, cam, T_wc, box, x0, x1, up.normalized(), label, cut, options, keyframe_floor,
                                masks, bottom_hidden);
  size_t begin = 0, end = 0;
  for (size_t i = 0, j = 0; i < samples.size(); ++i) {
    while (j < samples.size() && samples[j].z <= samples[i].z + band) ++j;
    if (edge_depth >= 0 && !(samples[i].z <= edge_depth && edge_depth <= samples[i].z + band)) continue;
    if (axis && samples[i].y > mid_row) continue;
    if (foot && !(samples[i].z >= foot->first && samples[i].z <= foot->second)) continue;
    if (j - i > end - begin) begin = i, end = j;
    if (thin && j - i >= need) break;
  }
  if (end - begin < need) return std::nullopt;
  if (begin >= end) return std::nullopt;
  // Most of the box lies inside the measured 3-D box of a nearer detection of its class whose image
  // box holds it (duplicate_containment), and what is left begins more than half the class's depth
  // behind that 3-D box, all in one class-deep window (duplicate_rest_window_share): the background
  // seen through that object, detected a second time (a chair's back inside the whole chair's box,
  // seen through its slats to the cabinet). Another object of the class hidden behind it would stand
  // next to it, show above it (a wheelchair far behind another), or show itself and what stands
  // around it at other depths (the far chairs of a row seen end on).
  if (inside_same_class > o.max_inside_same_class_share * valid) {
    double far = -1;
    const double area = w * h;
    for (const auto& m : masks)
      if (m.same_class && area > 0 && box_intersection(box, m.box) / area >= o.duplicate_containment)
        far = std::max(far, m.box_far_depth);
    const bool one_surface = static_cast<double>(end - begin) >= o.duplicate_rest_window_share * samples.size();
    if (far > 0 && samples[begin].z > far + 0.5 * band && one_surface) {
      if (duplicate) *duplicate = true;
      return std::nullopt;
    }
  }
  std::vector<Eigen::Vector3d> world;
  world.reserve(end - begin);
  for (size_t i = begin; i < end; ++i) world.push_back(samples[i].p);

  // Principal horizontal axis.
  const Eigen::Vector3d z = up.normalized();
  const Eigen::Vector3d e1 = z.unitOrthogonal(), e2 = z.cross(e1);
  Eigen::Vector2d mean2 = Eigen::Vector2d::Zero();
  for (const auto& p : world) mean2 += Eigen::Vector2d(p.dot(e1), p.dot(e2));
  mean2 /= world.size();
  Eigen::Matrix2d C = Eigen::Matrix2d::Zero();
  for (const auto& p : world) {
    const Eigen::Vector2d d = Eigen::Vector2d(p.dot(e1), p.dot(e2)) - mean2;
    C += d * d.transpose();
  }
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eig(C);
  const Eigen::Vector2d major = eig.eigenvectors().col(1);
  // A plane_axes_classes class: the axes of its vertical faces, and where those faces stand.
  std::vector<FacePoint> faces;
  std::optional<Eigen::Vector3d> face_axis_dir;
  if (o.axes_from_planes && options.plane_axes_classes.count(label)) {
    std::vector<std::pair<cv::Point, Eigen::Vector3d>> pixels;  // the window's samples: their points are known
    for (size_t i = begin; i < end; ++i) pixels.emplace_back(cv::Point(samples[i].x, samples[i].y), samples[i].p);
    faces = vertical_face_points(depth, cam, T_wc, pixels, z, std::max(2, stride));
    face_axis_dir = vertical_face_axis(faces, world, z, e1, e2, o.min_points);
  }
  const Eigen::Matrix3d R = upright_rotation(z, face_axis_dir ? *face_axis_dir : Eigen::Vector3d(major(0) * e1 + major(1) * e2));

  // Extents along the object axes.
  std::vector<double> ax[3];
  for (const auto& p : world)
    for (int k = 0; k < 3; ++k) ax[k].push_back(p.dot(R.col(k)));
  Eigen::Vector3d lo, hi;
  for (int k = 0; k < 3; ++k) lo(k) = percentile(ax[k], 0.05), hi(k) = percentile(ax[k], 0.95);
  Eigen::Vector3d size = (hi - lo).cwiseMax(0.02);
  // Far larger than the class allows: the points are wall or floor, not the object.
  if (sized) {
    const double largest = std::max({class_size->second[0], class_size->second[1], class_size->second[2]});
    if (size.maxCoeff() > o.max_size_ratio * largest) return std::nullopt;
  }
  if (!o.complete_depth_with_class_size || !sized) return ObjectPose{slam::SE3(R, R * (0.5 * (lo + hi))), size};
  const auto& cs = class_size->second;
  // A bottom cut is completed downwards as if it hid the object's lower part. When the lowest rows of
  // the object's points show a horizontal surface instead (a bed's top seen from above as the camera
  // passes close), the cut hides the object's near end, whose extent is unknown: no pose. A box that
  // ends within bottom_cut_reach of its height above the border is cut there when that surface fills
  // the rows below it. Only classes as long as bottom_face_min_length: a short top (a cabinet's) is
  // mostly seen, and its completion stays close.
  if (!thin && o.bottom_face_band > 0 && std::max(cs[0], cs[1]) >= o.bottom_face_min_length) {
    std::vector<std::pair<int, Eigen::Vector3d>> rows;
    for (size_t i = begin; i < end; ++i) rows.emplace_back(samples[i].y, samples[i].p);
    if (const auto top = bottom_rows_top_height(rows, T_wc.translation(), z, y0, y1, o.bottom_face_band)) {
      const bool near_border = box(3) >= depth.rows - 1 - std::max<double>(m, o.bottom_cut_reach * h);
      if (cut.bottom || (near_border && surface_reaches_bottom_border(depth, cam, T_wc, box, x0, x1, z, *top,
                                                                       o.top_surface_tolerance)))
        return std::nullopt;
    }
  }

  const bool flat = std::min(cs[0], cs[1]) <= o.flat_ratio * std::max(cs[0], cs[1]);
  // A flat class's face runs along its larger horizontal extent.
  const auto face_axis = [&]() { return hi(0) - lo(0) >= hi(1) - lo(1) ? 0 : 1; };
  // The vertical ends from the box's uncut top and bottom rows: the heights where the rays through
  // them meet the object (`height_at(row, top)`); a cut end is completed to the class's height.
  const auto ends_from_rows = [&](const std::function<std::optional<double>(double, bool)>& height_at) {
    if (!cut.top)
      if (const auto top = height_at(box(1), true)) hi(2) = *top;
    if (!cut.bottom)
      if (const auto bottom = height_at(box(3), false)) lo(2) = *bottom;
    if (cut.bottom) lo(2) = hi(2) - std::max(hi(2) - lo(2), cs[2]);
    if (cut.top) hi(2) = lo(2) + std::max(hi(2) - lo(2), cs[2]);
  };
  if (thin && o.thin_height_from_box_rows) {
    // A thin class's lower part (legs, wheels, a base of spokes) gives few points and its top (a
    // backrest, a hook) few more: the 5-95 % extent falls short of both ends. Its rows are met at
    // the depth of its points, at the box's middle column.
    const double d = samples[(begin + end) / 2].z, u = 0.5 * (box(0) + box(2));
    ends_from_rows([&](double row, bool) -> std::optional<double> {
      return (T_wc * (cam.unproject(Eigen::Vector2d(u, row)) * d)).dot(z);
    });
  } else if (flat && o.flat_height_from_box_rows) {
    // A flat class's trimmed rows (box_shrink) span about 60 % of its face (a door). Its top and
    // bottom rows are those of its nearer end, at the box's left or right edge: the rays through
    // both edges meet the vertical plane of its points (across its thinner horizontal extent), the
    // far edge's ray above the top and below the bottom when the face is seen obliquely. The lower
    // top and the higher bottom are the face's.
    // An end inside the points' extent, or one past 1.25 class heights from it (a ray grazing the
    // face), keeps the points' end.
    const int a = face_axis();
    const Eigen::Vector3d mid = R * (0.5 * (lo + hi));
    const double points_lo = lo(2), points_hi = hi(2), reach = 1.25 * cs[2];
    ends_from_rows([&](double row, bool top) -> std::optional<double> {
      std::optional<double> h;
      for (const double col : {box(0), box(2)})
        if (const auto p = ray_meets_plane(cam, T_wc, Eigen::Vector2d(col, row), mid, R.col(1 - a)))
          h = !h ? p->dot(z) : top ? std::min(*h, p->dot(z)) : std::max(*h, p->dot(z));
      if (h && (top ? *h < points_hi || *h > points_lo + reach : *h > points_lo || *h < points_hi - reach)) h.reset();
      return h;
    });
  } else if (cut.bottom || cut.top) {
    // A box cut at the top or bottom: the sampled vertical extent ends short of the box's uncut edge
    // by the trimmed margin (box_shrink and the 5 % tail, as a share of the sampled extent); from that
    // real end the object spans the class's height.
    const double trim = (o.box_shrink + 0.05 * (1 - 2 * o.box_shrink)) / (0.9 * (1 - 2 * o.box_shrink));
    const double seen = (hi(2) - lo(2)) * (1 + 2 * trim), full = std::max(seen, cs[2]);
    if (cut.bottom)
      hi(2) += trim * (hi(2) - lo(2)), lo(2) = hi(2) - full;
    else
      lo(2) -= trim * (hi(2) - lo(2)), hi(2) = lo(2) + full;
  }
  // A side cut (not of a thin class: its nearest points show no face): completed along the seen
  // face, towards the cut border.
  int cut_axis = -1;
  double cut_other = 0;  // the class's horizontal size the other axis then gets
  if (side) {
    const slam::SE3 T_cw = T_wc.inverse();
    const Eigen::Vector3d pc = T_cw * (R * (0.5 * (lo + hi)));
    if (pc.z() <= 1e-6) return std::nullopt;
    // The hidden part continues the seen face: along the major axis (R.col(0)), on the side where
    // the image moves towards the cut border. du: image columns per metre along that axis.
    const int a = 0;
    const Eigen::Vector3d d = T_cw.rotation() * R.col(a);
    const double du = cam.fx * (d.x() * pc.z() - pc.x() * d.z()) / (pc.z() * pc.z());
    if (std::abs(du) < o.side_cut_min_slope) return std::nullopt;  // the face runs along the ray
    const double sign = (du < 0) == cut.left ? 1.0 : -1.0;  // + : the cut lies towards +R.col(a)
    // The uncut end: where the ray through the box's uncut edge meets the face (the vertical plane
    // along R.col(a) through the window's points in the edge columns).
    Eigen::Vector3d edge = Eigen::Vector3d::Zero();
    int n = 0;
    for (size_t i = begin; i < end; ++i)
      if (at_uncut_edge(samples[i])) edge += samples[i].p, ++n;
    if (n == 0) return std::nullopt;
    edge /= n;
    const Eigen::Vector3d normal = R.col(1 - a);
    const Eigen::Vector2d edge_pixel(cut.left ? box(2) : box(0), cam.project(T_cw * edge).y());
    const auto end_point = ray_meets_plane(cam, T_wc, edge_pixel, edge, normal);
    if (!end_point) return std::nullopt;
    const double end_a = end_point->dot(R.col(a));
    const double seen = sign > 0 ? hi(a) - end_a : end_a - lo(a);
    // The class's horizontal sizes the seen part can be a piece of (10 % tolerance); two unlike ones
    // (a bed's width or length) leave the completion unknown: no pose. So does an end far from the
    // edge points (a ray grazing a face that is not one: a bed's top and side).
    const double small = std::min(cs[0], cs[1]), large = std::max(cs[0], cs[1]);
    if (seen > 1.1 * large || std::abs(end_a - edge.dot(R.col(a))) > 0.5 * large) return std::nullopt;
    const bool small_fits = small >= 0.9 * seen;
    if (small_fits && large > 1.25 * small) return std::nullopt;
    const double full = small_fits ? std::max(seen, small) : std::max(seen, large);
    if (sign > 0)
      lo(a) = end_a, hi(a) = end_a + full;
    else
      hi(a) = end_a, lo(a) = end_a - full;
    cut_axis = a;
    cut_other = full <= small ? large : small;
  }
  // A flat class's face (a door) ends where the rays through the box's left and right edges meet
  // it: the trimmed points' 5-95 % extent falls short of both ends, more at the near end of an
  // oblique face (nearer columns hold more points per metre). A grazing face keeps the points' extent.
  if (flat && !side) {
    const int a = face_axis();
    const Eigen::Vector3d mid = R * (0.5 * (lo + hi));
    const double row = cam.project(T_wc.inverse() * mid).y();
    const auto e0 = ray_meets_plane(cam, T_wc, Eigen::Vector2d(box(0), row), mid, R.col(1 - a));
    const auto e1 = ray_meets_plane(cam, T_wc, Eigen::Vector2d(box(2), row), mid, R.col(1 - a));
    if (e0 && e1) {
      const auto [s0, s1] = std::minmax({e0->dot(R.col(a)), e1->dot(R.col(a))});
      if (s0 <= lo(a) && s1 >= hi(a) && s1 - s0 <= 1.25 * std::max(cs[0], cs[1])) lo(a) = s0, hi(a) = s1;
    }
  }
  size = (hi - lo).cwiseMax(0.02);
  Eigen::Vector3d centre = R * (0.5 * (lo + hi));

  // Only the camera-facing surface is seen: the depth comes from the class's typical size (after a
  // side cut, along the other axis).
  Eigen::Vector3d view = centre - T_wc.translation();
  view -= view.dot(z) * z;
  if (view.norm() > 1e-6) {
    view.normalize();
    // The horizontal object axis closer to the viewing direction is the hidden depth.
    int k = std::abs(view.dot(R.col(0))) > std::abs(view.dot(R.col(1))) ? 0 : 1;
    if (cut_axis >= 0)
      k = 1 - cut_axis;
    else if (flat)
      k = size(0) < size(1) ? 0 : 1;  // a flat class's face normal
    // The class's horizontal size that is not the seen width is the hidden depth.
    const double other_seen = size(1 - k);
    const double expected = cut_axis >= 0 ? cut_other
                            : std::abs(other_seen - cs[0]) < std::abs(other_seen - cs[1]) ? cs[1] : cs[0];
    // Anchor on the front surface (the extent end facing the camera): what lies behind it in the
    // box may be the object's back or the wall it stands against.
    const double sign = view.dot(R.col(k)) >= 0 ? 1.0 : -1.0;
    double front = sign > 0 ? lo(k) : hi(k);
    // A class whose nearest parts stand low (a wheelchair's footplate and casters) shows them only in
    // the bottom rows that box_shrink trims off: its front is the nearer of where the ray through the
    // box's bottom row meets the floor just below the box and where those rows' parts above the floor
    // begin, when that lies nearer than the points' front, by less than the class's depth.
    if (o.front_from_foot && options.foot_front_classes.count(label) && cut_axis < 0) {
      const auto floor = cut.bottom ? std::nullopt : floor_below_box(depth, cam, T_wc, box, x0, x1, z, o.floor_spread);
      const double points_front = front;
      const auto take_if_nearer = [&](double f) {
        if (sign * (front - f) > 0 && sign * (points_front - f) < expected) front = f;
      };
      if (floor) {
        const Eigen::Vector2d foot_pixel(0.5 * (box(0) + box(2)), box(3));
        if (const auto foot = ray_meets_plane(cam, T_wc, foot_pixel, *floor * z, z)) take_if_nearer(foot->dot(R.col(k)));
        // The parts standing just above the floor in the trimmed bottom rows (a footplate in front of
        // the casters whose floor contact the bottom row shows).
        if (o.front_from_low_rows)
          if (const auto low = low_rows_extent(depth, cam, T_wc, masks, y1 + 1, static_cast<int>(box(3)), x0, x1,
                                               std::max(o.min_depth, samples[begin].z - expected), samples[end - 1].z,
                                               z, *floor + o.floor_clearance, R.col(k), sign > 0 ? 0.1 : 0.9))
            take_if_nearer(*low);
      }
      if (cut.bottom && o.centre_from_upper_part_when_cut) {
        std::vector<double> upper;
        for (const auto& p : world)
          if (p.dot(z) >= hi(2) - 0.5 * cs[2]) upper.push_back(p.dot(R.col(k)));
        if (static_cast<int>(upper.size()) >= o.min_points)
          take_if_nearer(0.5 * (percentile(upper, 0.05) + percentile(upper, 0.95)) - sign * 0.5 * expected);
      }
    }
    // An axis class's points are mostly its shaft: their median depth along k is the axis.
    const double along = axis ? percentile(ax[k], 0.5) : front + sign * 0.5 * expected;
    centre += (along - centre.dot(R.col(k))) * R.col(k);
    size(k) = expected;
    // A thin class is measured on its nearest surface only (a chair's seat edge and front legs): its
    // seen width and height fall short of the object's. The centre stays; the box gets the class's
    // size at least, so that the map shows a chair, not a slab.
    if (thin || (o.solid_class_size_floor && !flat)) {
      const double width = expected == cs[0] ? cs[1] : cs[0];
      size(1 - k) = std::max(size(1 - k), width);
      size(2) = std::max(size(2), cs[2]);
    }
    // Seen at a slant, a plane_axes_classes class shows the face across its other axis too (a bed's
    // side beside its foot): the points' middle along that axis lies towards the camera (the far
    // side is hidden or trimmed), so the centre is that face pushed back by half the box's size.
    // Only a face in the near quarter of the points' extent is the object's side; one farther back
    // faces the camera from behind the object or inside it (a wall beyond a bed's far side, seen
    // past the bed from its foot: aisle_right_turn's bed 12 was pushed 1 m onto it).
    const int j = 1 - k;
    if (face_axis_dir && cut_axis < 0 && o.anchor_side_face)
      if (const auto face = seen_face(faces, R.col(j), o.min_points);
          face && face->second * (face->first - 0.5 * (lo(j) + hi(j))) >= 0.25 * (hi(j) - lo(j))) {
        const double mid = face->first - face->second * 0.5 * size(j);
        centre += (mid - centre.dot(R.col(j))) * R.col(j);
      }
  }
  // A tall class (a door, a pole) spans its box's rows: its height and the box's height bound its
  // distance. A pole owns few of its box's pixels, and its depth window can land on the wall behind.
  if (!cut.top && !cut.bottom && o.tall_depth_ratio > 0 && cs[2] >= o.tall_class_ratio * std::max(cs[0], cs[1])) {
    const double depth_from_height = cam.fy * cs[2] / h;  // tall_depth_ratio's margin covers the centre's offset
    if ((T_wc.inverse() * centre).z() > o.tall_depth_ratio * depth_from_height) return std::nullopt;
  }
  return ObjectPose{slam::SE3(R, centre), size};
}

}  // namespace

namespace {

// Valid depths sampled over the trimmed box (about target_samples of them), without those inside
// `exclude`.
std::vector<double> box_depth_samples(const cv::Mat& depth, const Eigen::Vector4d& box, const MeasurementOptions& o,
                                      const Eigen::Vector4d* exclude) {
  std::vector<double> zs;
  if (depth.empty()) return zs;
  const double w = box(2) - box(0), h = box(3) - box(1);
  const int x0 = std::max(0, static_cast<int>(box(0) + o.box_shrink * w));
  const int x1 = std::min(depth.cols - 1, static_cast<int>(box(2) - o.box_shrink * w));
  const int y0 = std::max(0, static_cast<int>(box(1) + o.box_shrink * h));
  const int y1 = std::min(depth.rows - 1, static_cast<int>(box(3) - o.box_shrink * h));
  if (x1 < x0 || y1 < y0) return zs;
  const int stride = std::max(1, static_cast<int>(std::sqrt((x1 - x0 + 1.0) * (y1 - y0 + 1.0) / o.target_samples)));
  for (int y = y0; y <= y1; y += stride)
    for (int x = x0; x <= x1; x += stride) {
      if (exclude && x >= (*exclude)(0) && x <= (*exclude)(2) && y >= (*exclude)(1) && y <= (*exclude)(3)) continue;
      const double z = depth.at<float>(y, x);
      if (z >= o.min_depth && z <= o.max_depth) zs.push_back(z);
    }
  return zs;
}

// Support box `b` (a table) much larger than box `a` and holding most of it: what `a` stands on or in
// front of.
bool holds_as_support(const Eigen::Vector4d& a, const Eigen::Vector4d& b, const MeasurementOptions& o) {
  const double area_a = (a(2) - a(0)) * (a(3) - a(1)), area_b = (b(2) - b(0)) * (b(3) - b(1));
  return area_a > 0 && box_intersection(a, b) / area_a > o.support_containment && area_b > o.support_area_ratio * area_a;
}

}  // namespace

double box_median_depth(const cv::Mat& depth, const Eigen::Vector4d& box, const MeasurementOptions& o,
                        const Eigen::Vector4d* exclude) {
  std::vector<double> zs = box_depth_samples(depth, box, o, exclude);
  return static_cast<int>(zs.size()) < (exclude ? o.min_points : 1) ? 0.0 : percentile(zs, 0.5);
}

double box_front_share(const cv::Mat& depth, const Eigen::Vector4d& box, const MeasurementOptions& o) {
  std::vector<double> zs = box_depth_samples(depth, box, o, nullptr);
  if (zs.empty()) return 0.0;
  const double median = percentile(zs, 0.5);  // (reorders zs)
  const auto front = std::count_if(zs.begin(), zs.end(), [&](double z) { return z < median - o.occluder_margin; });
  return static_cast<double>(front) / static_cast<double>(zs.size());
}

std::vector<std::vector<int>> nearer_overlapping_detections(const cv::Mat& depth, const std::vector<Eigen::Vector4d>& boxes,
                                                            const MeasurementOptions& o,
                                                            const std::vector<bool>& supports) {
  std::vector<double> z(boxes.size());
  for (size_t i = 0; i < boxes.size(); ++i) z[i] = box_median_depth(depth, boxes[i], o);
  std::vector<std::vector<int>> out(boxes.size());
  for (size_t i = 0; i < boxes.size(); ++i)
    for (size_t j = 0; j < boxes.size(); ++j) {
      if (i == j) continue;
      const auto& a = boxes[i];
      const auto& b = boxes[j];
      if (!(std::min(a(2), b(2)) > std::max(a(0), b(0)) && std::min(a(3), b(3)) > std::max(a(1), b(1)))) continue;
      // Nearer: clearly less deep, or (objects standing on the floor, camera upright) its box reaches
      // clearly lower in the image. The depths compared are those of the parts of the two boxes that
      // do not overlap: the overlap shows the nearer one in both (a chair far behind another one
      // would otherwise look as near as it). A box inside the other one has no such part: whole boxes.
      double zi = box_median_depth(depth, a, o, &b), zj = box_median_depth(depth, b, o, &a);
      if (zi <= 0 || zj <= 0) zi = z[i], zj = z[j];
      const bool nearer_by_depth = zj > 0 && zi > 0 && zj < zi - o.occluder_margin;
      const bool nearer_by_footprint = b(3) > a(3) + o.occluder_footprint_px;
      if (!nearer_by_depth && !nearer_by_footprint) continue;
      // A much larger box that holds most of mine is what I stand on or in front of (a cup on a
      // table), not an occluder; a neighbour of my size in front of me is.
      const bool support = j < supports.size() && supports[j];
      if (support && !nearer_by_depth && holds_as_support(a, b, o)) continue;
      out[i].push_back(static_cast<int>(j));
    }
  return out;
}

std::optional<ObjectPose> measure_pose_from_depth(const cv::Mat& depth, const slam::PinholeCamera& camera,
                                                  const slam::SE3& T_wc, const Eigen::Vector4d& box,
                                                  const Eigen::Vector3d& up, const std::string& label,
                                                  const SemanticOptions& options,
                                                  const std::vector<Occluder>& occluders) {
  return measure_pose(depth, camera, T_wc, box, up, label, options, occluders, false);
}

std::optional<ObjectPose> measure_thin_side_cut(const cv::Mat& depth, const slam::PinholeCamera& camera,
                                                const slam::SE3& T_wc, const Eigen::Vector4d& box,
                                                const Eigen::Vector3d& up, const std::string& label,
                                                const SemanticOptions& options,
                                                const std::vector<Occluder>& occluders) {
  return measure_pose(depth, camera, T_wc, box, up, label, options, occluders, true);
}

std::vector<std::optional<ObjectPose>> measure_keyframe_poses(const cv::Mat& depth, const slam::PinholeCamera& camera,
                                                              const slam::SE3& T_wc,
                                                              const std::vector<Eigen::Vector4d>& boxes,
                                                              const std::vector<std::string>& labels,
                                                              const Eigen::Vector3d& up, const SemanticOptions& options,
                                                              std::vector<std::optional<ObjectPose>>* side_cut_poses,
                                                              std::vector<bool>* duplicates) {
  const size_t n = boxes.size();
  std::vector<std::optional<ObjectPose>> poses(n);
  if (side_cut_poses) side_cut_poses->assign(n, std::nullopt);
  if (duplicates) duplicates->assign(n, false);
  if (depth.empty()) return poses;
  std::vector<bool> supports(n);
  for (size_t i = 0; i < n; ++i) supports[i] = options.support_classes.count(labels[i]) > 0;
  const auto nearer = nearer_overlapping_detections(depth, boxes, options.measurement, supports);
  // The keyframe's floor serves only the foot window: not looked for when that is off.
  const bool foot_window =
      std::any_of(labels.begin(), labels.end(), [&](const std::string& l) { return foot_window_applies(l, options); });
  const std::optional<double> floor =
      foot_window ? keyframe_floor(depth, camera, T_wc, boxes, up, options.measurement) : std::nullopt;
  std::vector<double> z;  // whole-box median depths, only needed to break a cycle
  // Front to back: a detection is measured once all its occluders are; when the "nearer" relation
  // has a cycle (nearer by depth one way, by footprint the other), the nearest pending one goes next
  // and its unmeasured occluders hide their whole boxes.
  std::vector<bool> done(n, false);
  for (size_t count = 0; count < n; ++count) {
    int next = -1;
    for (size_t i = 0; i < n && next < 0; ++i)
      if (!done[i] && std::all_of(nearer[i].begin(), nearer[i].end(), [&](int j) { return done[j]; }))
        next = static_cast<int>(i);
    if (next < 0 && z.empty())
      for (size_t i = 0; i < n; ++i) z.push_back(box_median_depth(depth, boxes[i], options.measurement));
    if (next < 0)
      for (size_t i = 0; i < n; ++i)
        if (!done[i] && (next < 0 || z[i] < z[next])) next = static_cast<int>(i);
    std::vector<Occluder> occluders;
    for (int j : nearer[next]) {
      // An unplaced support holding the box (a table cut by the border, its near edge nearer than a
      // cup on its far half) cannot say which pixels are its own, and its whole box would hide what
      // stands on it: it hides nothing when the box shows hardly anything in front of its own depth
      // (measurement.support_front_share), else its whole box (a bed in front of a cabinet).
      if (supports[j] && !poses[j] && holds_as_support(boxes[next], boxes[j], options.measurement) &&
          box_front_share(depth, boxes[next], options.measurement) <= options.measurement.support_front_share)
        continue;
      occluders.push_back({boxes[j], done[j] ? poses[j] : std::nullopt, labels[j] == labels[next],
                           options.box_masked_classes.count(labels[j]) > 0, supports[j]});
    }
    bool duplicate = false;
    poses[next] =
        measure_pose(depth, camera, T_wc, boxes[next], up, labels[next], options, occluders, false, &duplicate, floor);
    if (duplicates) (*duplicates)[next] = duplicate;
    if (side_cut_poses && !poses[next] && nearer[next].empty())
      (*side_cut_poses)[next] =
          measure_thin_side_cut(depth, camera, T_wc, boxes[next], up, labels[next], options, occluders);
    done[next] = true;
  }
  drop_coincident_poses(poses, boxes, labels, up, camera, T_wc, options);
  return poses;
}

std::optional<Eigen::Vector4d> project_box(const ObjectPose& box, const slam::PinholeCamera& camera, const slam::SE3& T_wc) {
  const slam::SE3 T_cw = T_wc.inverse();
  constexpr double near = 0.1;  // m in front of the camera
  std::array<Eigen::Vector3d, 8> corners;
  for (int c = 0; c < 8; ++c) {
    const Eigen::Vector3d corner(c & 1 ? 0.5 : -0.5, c & 2 ? 0.5 : -0.5, c & 4 ? 0.5 : -0.5);
    corners[c] = T_cw * (box.pose * corner.cwiseProduct(box.size));
  }
  Eigen::Vector4d b(1e18, 1e18, -1e18, -1e18);
  const auto add = [&](const Eigen::Vector3d& p) {
    const Eigen::Vector2d uv = camera.project(p);
    b = Eigen::Vector4d(std::min(b(0), uv.x()), std::min(b(1), uv.y()), std::max(b(2), uv.x()), std::max(b(3), uv.y()));
  };
  // The part of the box in front of the near plane: its corners there, and where its edges cross it.
  for (int c = 0; c < 8; ++c) {
    if (corners[c].z() >= near) add(corners[c]);
    for (const int bit : {1, 2, 4}) {
      const int d = c | bit;
      if (d == c || (corners[c].z() >= near) == (corners[d].z() >= near)) continue;
      const double t = (near - corners[c].z()) / (corners[d].z() - corners[c].z());
      add(corners[c] + t * (corners[d] - corners[c]));
    }
  }
  if (b(2) < b(0)) return std::nullopt;  // wholly behind it
  b = b.cwiseMax(Eigen::Vector4d::Zero())
          .cwiseMin(Eigen::Vector4d(camera.width - 1, camera.height - 1, camera.width - 1, camera.height - 1));
  if (b(2) <= b(0) || b(3) <= b(1)) return std::nullopt;
  return b;
}

void drop_coincident_poses(std::vector<std::optional<ObjectPose>>& poses, const std::vector<Eigen::Vector4d>& boxes,
                           const std::vector<std::string>& labels, const Eigen::Vector3d& up,
                           const slam::PinholeCamera& camera, const slam::SE3& T_wc, const SemanticOptions& options) {
  const MeasurementOptions& o = options.measurement;
  const bool check_ambiguous = o.ambiguous_pair_iou <= 1;
  if (o.coincident_ratio <= 0 && !check_ambiguous) return;
  const Eigen::Vector3d z = up.normalized();
  const auto footprint = [&](size_t i) {
    const auto cs = options.class_sizes.find(labels[i]);
    if (cs != options.class_sizes.end()) return std::min(cs->second[0], cs->second[1]);
    return std::min(poses[i]->size(0), poses[i]->size(1));
  };
  std::vector<bool> drop(poses.size(), false);
  for (size_t i = 0; i < poses.size(); ++i)
    for (size_t j = i + 1; j < poses.size(); ++j) {
      if (!poses[i] || !poses[j] || options.support_classes.count(labels[i]) || options.support_classes.count(labels[j]))
        continue;
      Eigen::Vector3d d = poses[i]->pose.translation() - poses[j]->pose.translation();
      d -= d.dot(z) * z;
      const bool coincident = d.norm() < o.coincident_ratio * std::min(footprint(i), footprint(j));
      const bool ambiguous =
          check_ambiguous && labels[i] == labels[j] && box_iou(boxes[i], boxes[j]) >= o.ambiguous_pair_iou;
      if (!coincident && !ambiguous) continue;
      const double lower = boxes[i](3) - boxes[j](3);  // > 0: i reaches lower, so it is nearer
      if (std::abs(lower) <= o.occluder_footprint_px && coincident) {
        // Which box does the object at that place fill? favours(k) > 0: pose k projects onto box i
        // better than onto box j.
        const auto favours = [&](size_t k) {
          const auto proj = project_box(*poses[k], camera, T_wc);
          return proj ? box_iou(*proj, boxes[i]) - box_iou(*proj, boxes[j]) : 0.0;
        };
        const double a = favours(i), b = favours(j), m = o.coincident_projection_margin;
        if (a >= m && b <= -m) continue;  // each fills its own box: two objects, one placed a little off
        if (a + b >= 2 * m || a + b <= -2 * m) {  // both measured on the object of one box
          drop[a + b > 0 ? j : i] = true;
          continue;
        }
      }
      if (lower <= o.occluder_footprint_px) drop[i] = true;
      if (lower >= -o.occluder_footprint_px) drop[j] = true;
    }
  for (size_t i = 0; i < poses.size(); ++i)
    if (drop[i]) poses[i].reset();
}

}  // namespace wardmap::semantics
