#include "semantics/object_association.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <functional>
#include <iterator>
#include <limits>
#include <map>
#include <optional>
#include <set>
#include <tuple>
#include <thread>

#include "hdp/crf_sampler.h"
#include "hdp/suffix_swap.h"
#include "mot/hungarian.h"
#include "mot/tracker.h"
#include "semantics/object_metrics.h"
#include "semantics/pose_selection.h"

namespace wardmap::semantics {

namespace {

int class_index(const std::string& label, std::map<std::string, int>& classes) {
  return classes.emplace(label, static_cast<int>(classes.size())).first->second;
}

GroupObject make_group_object(int group, const std::vector<int>& ids, const std::vector<ObjectMeasurement>& ms) {
  GroupObject o;
  o.group = group;
  o.measurements = ids;
  std::sort(o.measurements.begin(), o.measurements.end());
  o.keyframe_measurements = keyframe_measurements_of(o.measurements, ms);
  std::map<std::string, int> votes;
  for (int id : o.measurements) {
    const auto& m = ms[id];
    ++votes[m.label];
    if (m.pose) o.features.push_back(pose_feature(*m.pose));
    if (m.embedding.size() > 0) o.embedding = o.embedding.size() ? Eigen::VectorXf(o.embedding + m.embedding) : m.embedding;
  }
  o.label = std::max_element(votes.begin(), votes.end(), [](auto& a, auto& b) { return a.second < b.second; })->first;
  if (o.embedding.size() > 0 && o.embedding.norm() > 0) o.embedding.normalize();
  return o;
}

// Whether a world point lies inside a landmark's footprint (its box seen from above), or with
// `whole_box` inside its 3-D box.
bool inside_box(const ObjectPose& box, const Eigen::Vector3d& p, bool whole_box = false) {
  const Eigen::Vector3d local = box.pose.inverse() * p;
  return std::abs(local.x()) <= 0.5 * box.size.x() && std::abs(local.y()) <= 0.5 * box.size.y() &&
         (!whole_box || std::abs(local.z()) <= 0.5 * box.size.z());
}

// Whether either box's footprint holds the other's centre.
bool footprints_meet(const ObjectPose& a, const ObjectPose& b) {
  return inside_box(a, b.pose.translation()) || inside_box(b, a.pose.translation());
}

// The most of the measurements `ids` that lie in `n` adjacent groups (group_of: per measurement;
// -1, none, is not counted).
int most_in_adjacent_groups(const std::vector<int>& ids, const std::vector<int>& group_of, int n) {
  std::vector<int> g;
  for (int id : ids)
    if (group_of[static_cast<size_t>(id)] >= 0) g.push_back(group_of[static_cast<size_t>(id)]);
  std::sort(g.begin(), g.end());
  int most = 0;
  for (size_t i = 0, j = 0; j < g.size(); ++j) {
    while (g[j] - g[i] >= n) ++i;
    most = std::max(most, static_cast<int>(j - i + 1));
  }
  return most;
}

// Landmark indices, most measurements first (the earlier on a tie).
std::vector<size_t> strongest_first(const std::vector<ObjectLandmark>& landmarks) {
  std::vector<size_t> order(landmarks.size());
  for (size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) {
    return landmarks[a].measurements.size() > landmarks[b].measurements.size();
  });
  return order;
}

// Whether at least half of the measurements' boxes lie within `margin` pixels of the image's left
// or right border (association.border_min_measurements, border_min_placed_measurements).
bool mostly_at_side_border(const std::vector<int>& ids, const std::vector<ObjectMeasurement>& ms,
                           const slam::PinholeCamera& camera, double margin) {
  int at = 0;
  for (int id : ids) {
    const Eigen::Vector4d& b = ms[id].box;
    if (b(0) <= margin || b(2) >= camera.width - 1 - margin) ++at;
  }
  return 2 * at >= static_cast<int>(ids.size());
}

void erase_gone(std::vector<ObjectLandmark>& landmarks, const std::vector<bool>& gone) {
  std::vector<ObjectLandmark> kept;
  for (size_t i = 0; i < landmarks.size(); ++i)
    if (!gone[i]) kept.push_back(std::move(landmarks[i]));
  landmarks = std::move(kept);
}

// The image box of a landmark's 3-D box in keyframe `kf` (project_box).
std::optional<Eigen::Vector4d> projected_box(const ObjectPose& box, const KeyframeViews& views, int kf) {
  return project_box(box, views.camera, views.T_wc[kf]);
}

// A landmark reported only through the side-border minimums whose boxes, in at least half of its
// keyframes, lie where a landmark of its class reported on its own projects (IoU at least
// `min_iou`) was measured on that object (a pole cut by the border, its few placed measurements
// low and off): it is dropped, its measurements left without a landmark, as they were without the
// border minimums. With `other_classes`, a landmark of another class counts too in the keyframes
// where it has no measurement: there the detector gave its object the wrong class (a bed at the
// border detected as a chair).
void drop_border_landmarks_on_others(std::vector<ObjectLandmark>& landmarks, const std::vector<bool>& border_only,
                                     const std::vector<ObjectMeasurement>& ms, const KeyframeViews& views,
                                     double min_iou, bool other_classes) {
  std::vector<std::set<int>> keyframes(landmarks.size());
  for (size_t j = 0; j < landmarks.size(); ++j)
    for (int id : landmarks[j].measurements) keyframes[j].insert(ms[id].keyframe);
  std::vector<bool> gone(landmarks.size(), false);
  for (size_t i = 0; i < landmarks.size(); ++i) {
    if (!border_only[i]) continue;
    int on_other = 0;
    for (int id : landmarks[i].measurements) {
      const ObjectMeasurement& m = ms[id];
      if (m.keyframe < 0 || m.keyframe >= static_cast<int>(views.T_wc.size())) continue;
      for (size_t j = 0; j < landmarks.size(); ++j) {
        if (border_only[j]) continue;
        if (landmarks[j].label != landmarks[i].label && (!other_classes || keyframes[j].count(m.keyframe))) continue;
        const auto b = projected_box(landmarks[j].pose, views, m.keyframe);
        if (b && box_iou(*b, m.box) >= min_iou) {
          ++on_other;
          break;
        }
      }
    }
    gone[i] = 2 * on_other >= static_cast<int>(landmarks[i].measurements.size());
  }
  erase_gone(landmarks, gone);
}

}  // namespace

ObjectLandmark* place_apart(ObjectLandmark& a, ObjectLandmark& b, const std::vector<ObjectMeasurement>& ms,
                            const std::function<void(ObjectLandmark&)>& place, int min_placed, const FreePose& free) {
  const auto outside = [&](const ObjectLandmark& l, const ObjectLandmark& other) {
    std::vector<int> ids;
    for (int id : l.measurements)
      if (ms[id].pose && !inside_box(other.pose, ms[id].pose->pose.translation())) ids.push_back(id);
    return ids;
  };
  const std::vector<int> outside_a = outside(a, b), outside_b = outside(b, a);
  const bool a_first = outside_a.size() >= outside_b.size();
  for (const bool move_a : {a_first, !a_first}) {
    ObjectLandmark& moved = move_a ? a : b;
    const ObjectLandmark& other = move_a ? b : a;
    ObjectLandmark probe;
    probe.label = moved.label;
    probe.measurements = move_a ? outside_a : outside_b;
    if (static_cast<int>(probe.measurements.size()) < std::max(1, min_placed)) continue;
    place(probe);
    if (footprints_meet(other.pose, probe.pose) || (free && !free(moved, probe.pose))) continue;
    moved.pose = probe.pose;
    moved.pose_measurement = probe.pose_measurement;
    return &moved;
  }
  return nullptr;
}

void merge_contained_landmarks(std::vector<ObjectLandmark>& landmarks,
                               const std::function<void(ObjectLandmark&)>& place,
                               const std::function<bool(const ObjectLandmark&, const ObjectLandmark&)>& never_together,
                               const PlaceApart& place_apart) {
  // Each landmark is tested against the stronger ones that are still kept, with their poses after
  // any merge.
  const std::vector<size_t> order = strongest_first(landmarks);
  std::vector<bool> gone(landmarks.size(), false);
  // Clear of every other kept landmark of its class (neither inside the other's footprint).
  const FreePose free = [&](const ObjectLandmark& l, const ObjectPose& pose) {
    for (size_t k = 0; k < landmarks.size(); ++k)
      if (!gone[k] && &landmarks[k] != &l && landmarks[k].label == l.label && footprints_meet(landmarks[k].pose, pose))
        return false;
    return true;
  };
  for (size_t oi = 1; oi < order.size(); ++oi) {
    ObjectLandmark& weak = landmarks[order[oi]];
    for (size_t si = 0; si < oi; ++si) {
      ObjectLandmark& strong = landmarks[order[si]];
      // Or the stronger one's centre inside the weaker one's footprint, if the two were never
      // measured in one keyframe: one of them turned wrongly puts the other's centre just outside
      // its footprint (two neighbours of a row, measured close, are seen together).
      if (gone[order[si]] || strong.label != weak.label ||
          !(inside_box(strong.pose, weak.pose.pose.translation()) ||
            (never_together && inside_box(weak.pose, strong.pose.pose.translation()) && never_together(strong, weak))))
        continue;
      if (place_apart && place_apart(weak, strong, free)) continue;  // two objects: one moved apart
      strong.measurements.insert(strong.measurements.end(), weak.measurements.begin(), weak.measurements.end());
      std::sort(strong.measurements.begin(), strong.measurements.end());
      place(strong);
      gone[order[oi]] = true;
      break;
    }
  }
  erase_gone(landmarks, gone);
}

namespace {

// Root of `i` in a disjoint-set forest, with path halving.
int root_of(std::vector<int>& parent, int i) {
  while (parent[i] != i) i = parent[i] = parent[parent[i]];
  return i;
}

// Tracks across groups: unplaced group objects of one class sharing a detection (an overlapping
// keyframe) are one; returns each one's root in the forest.
std::vector<int> unplaced_track_roots(const std::vector<std::vector<int>>& unplaced,
                                      const std::vector<std::string>& unplaced_labels) {
  std::vector<int> track(unplaced.size());
  for (size_t i = 0; i < track.size(); ++i) track[i] = static_cast<int>(i);
  std::map<int, int> holder;  // measurement id -> an unplaced group object holding it
  for (size_t i = 0; i < unplaced.size(); ++i)
    for (int id : unplaced[i]) {
      const auto [it, fresh] = holder.emplace(id, static_cast<int>(i));
      if (!fresh && unplaced_labels[it->second] == unplaced_labels[i])
        track[root_of(track, static_cast<int>(i))] = root_of(track, it->second);
    }
  for (size_t i = 0; i < track.size(); ++i) track[i] = root_of(track, static_cast<int>(i));
  return track;
}

}  // namespace

int link_through_unplaced_tracks(
    const std::vector<std::vector<int>>& unplaced, const std::vector<std::string>& unplaced_labels,
    const std::vector<std::string>& dish_labels, const std::vector<std::vector<int>>& dish_measurements,
    const std::vector<bool>& reportable,
    const std::function<bool(const std::vector<int>&, const std::vector<int>&)>& never_together,
    std::vector<int>& dish_of) {
  const std::vector<int> track = unplaced_track_roots(unplaced, unplaced_labels);
  std::map<int, std::set<int>> touched;  // track root -> same-class dishes its detections belong to
  for (size_t i = 0; i < unplaced.size(); ++i)
    for (int id : unplaced[i])
      if (dish_of[id] >= 0 && dish_labels[dish_of[id]] == unplaced_labels[i]) touched[track[i]].insert(dish_of[id]);

  std::vector<int> dish(dish_labels.size());
  for (size_t k = 0; k < dish.size(); ++k) dish[k] = static_cast<int>(k);
  // Per root: the measurements of the dishes merged into it (sorted), so that a chain of merges
  // never joins two dishes measured together.
  std::map<int, std::vector<int>> merged_measurements;
  const auto measurements_of = [&](int root) -> const std::vector<int>& {
    const auto it = merged_measurements.find(root);
    return it != merged_measurements.end() ? it->second : dish_measurements[static_cast<size_t>(root)];
  };
  int merged = 0;
  for (const auto& [t, all_dishes] : touched) {
    std::vector<int> dishes;
    for (int k : all_dishes)
      if (reportable[static_cast<size_t>(k)]) dishes.push_back(k);
    // A track touching two landmarks measured in one keyframe switched between objects: it
    // tells nothing about which of its landmarks are one.
    bool mixed = false;
    for (size_t a = 0; a < dishes.size() && !mixed; ++a)
      for (size_t b = a + 1; b < dishes.size() && !mixed; ++b)
        mixed = !never_together(dish_measurements[static_cast<size_t>(dishes[a])],
                                dish_measurements[static_cast<size_t>(dishes[b])]);
    if (mixed) continue;
    for (size_t a = 0; a < dishes.size(); ++a)
      for (size_t b = a + 1; b < dishes.size(); ++b) {
        const int ra = root_of(dish, dishes[a]), rb = root_of(dish, dishes[b]);
        if (ra == rb || !never_together(measurements_of(ra), measurements_of(rb))) continue;
        std::vector<int> joined;
        std::merge(measurements_of(ra).begin(), measurements_of(ra).end(), measurements_of(rb).begin(),
                   measurements_of(rb).end(), std::back_inserter(joined));
        merged_measurements.erase(std::max(ra, rb));
        merged_measurements[std::min(ra, rb)] = std::move(joined);
        dish[std::max(ra, rb)] = std::min(ra, rb);
        ++merged;
      }
  }
  for (auto& d : dish_of)
    if (d >= 0) d = root_of(dish, d);
  return merged;
}

namespace {

// Where an upright box's bottom lies along its up axis (poses are upright: their z axis is up).
double bottom_height(const ObjectPose& box) {
  return box.pose.translation().dot(box.pose.rotation_matrix().col(2)) - 0.5 * box.size(2);
}

// How far apart two upright boxes' centres stand, across `a`'s up axis.
double horizontal_distance(const ObjectPose& a, const ObjectPose& b) {
  const Eigen::Vector3d up = a.pose.rotation_matrix().col(2);
  Eigen::Vector3d d = a.pose.translation() - b.pose.translation();
  d -= d.dot(up) * up;
  return d.norm();
}

}  // namespace

std::optional<double> floor_height(const std::vector<ObjectLandmark>& landmarks, const std::set<std::string>& classes) {
  std::vector<double> bottoms;
  for (const auto& l : landmarks)
    if (classes.count(l.label)) bottoms.push_back(bottom_height(l.pose));
  if (bottoms.size() < 2) return std::nullopt;
  std::nth_element(bottoms.begin(), bottoms.begin() + bottoms.size() / 2, bottoms.end());
  return bottoms[bottoms.size() / 2];
}

std::vector<std::pair<std::string, std::vector<int>>> tracks_without_landmark(
    const std::vector<std::vector<int>>& unplaced, const std::vector<std::string>& unplaced_labels,
    const std::vector<int>& dish_of) {
  const std::vector<int> track = unplaced_track_roots(unplaced, unplaced_labels);
  std::map<int, std::set<int>> ids;  // track root -> its measurement ids
  std::set<int> held;                // roots of tracks with a measurement in a dish
  for (size_t i = 0; i < unplaced.size(); ++i)
    for (int id : unplaced[i]) {
      ids[track[i]].insert(id);
      if (dish_of[id] >= 0) held.insert(track[i]);
    }
  std::vector<std::pair<std::string, std::vector<int>>> out;
  for (const auto& [root, set] : ids)
    if (!held.count(root)) out.emplace_back(unplaced_labels[root], std::vector<int>(set.begin(), set.end()));
  return out;
}

void reassign_by_projection(std::vector<ObjectLandmark>& landmarks, const std::vector<ObjectMeasurement>& ms,
                            const KeyframeViews& views, double min_iou, double margin, bool placed_too) {
  std::map<int, int> landmark_of;  // measurement id -> landmark index
  for (size_t l = 0; l < landmarks.size(); ++l)
    for (int id : landmarks[l].measurements) landmark_of[id] = static_cast<int>(l);
  std::map<int, std::vector<int>> by_keyframe;
  for (const auto& [id, l] : landmark_of) by_keyframe[ms[id].keyframe].push_back(id);
  bool changed = false;
  for (const auto& [kf, ids] : by_keyframe) {
    if (kf < 0 || kf >= static_cast<int>(views.T_wc.size())) continue;
    std::vector<int> rows;
    std::set<int> taken;  // landmarks held in this keyframe by a measurement that stays
    for (int id : ids) {
      const int l = landmark_of[id];
      if (ms[id].pose && (!placed_too || landmarks[l].pose_measurement == id)) taken.insert(l);
      else rows.push_back(id);
    }
    if (rows.empty()) continue;
    std::vector<int> cols;
    std::vector<std::optional<Eigen::Vector4d>> projections;
    for (size_t l = 0; l < landmarks.size(); ++l)
      if (!taken.count(static_cast<int>(l))) {
        cols.push_back(static_cast<int>(l));
        projections.push_back(projected_box(landmarks[l].pose, views, kf));
      }
    if (cols.empty()) continue;
    Eigen::MatrixXd cost = Eigen::MatrixXd::Constant(rows.size(), cols.size(), std::numeric_limits<double>::infinity());
    for (size_t i = 0; i < rows.size(); ++i)
      for (size_t j = 0; j < cols.size(); ++j) {
        const ObjectMeasurement& m = ms[rows[i]];
        if (!projections[j] || landmarks[cols[j]].label != m.label) continue;
        const double iou = box_iou(*projections[j], m.box);
        if (iou < min_iou) continue;
        cost(i, j) = -(iou + (cols[j] == landmark_of[rows[i]] ? margin : 0.0));
      }
    for (const auto& [i, j] : mot::solve_assignment(cost, -min_iou).matches)
      if (landmark_of[rows[i]] != cols[j]) {
        landmark_of[rows[i]] = cols[j];
        changed = true;
      }
  }
  if (!changed) return;
  for (auto& l : landmarks) l.measurements.clear();
  for (const auto& [id, l] : landmark_of) landmarks[l].measurements.push_back(id);
}

int keep_one_per_keyframe(std::vector<ObjectLandmark>& landmarks, const std::vector<ObjectMeasurement>& ms,
                          const KeyframeViews* views, const std::function<void(ObjectLandmark&)>& place) {
  int removed = 0;
  for (ObjectLandmark& l : landmarks) {
    std::map<int, std::vector<int>> by_keyframe;
    for (int id : l.measurements) by_keyframe[ms[id].keyframe].push_back(id);
    // The measurements that leave, judged against the landmark's current projection.
    const auto losers = [&](const ObjectLandmark& judge) {
      std::set<int> off;
      for (const auto& [kf, ids] : by_keyframe) {
        if (ids.size() < 2) continue;
        std::optional<Eigen::Vector4d> projection;
        if (views && kf >= 0 && kf < static_cast<int>(views->T_wc.size()))
          projection = projected_box(judge.pose, *views, kf);
        // Ranked by (IoU with the projection, is the pose measurement, is placed, score).
        const auto rank = [&](int id) {
          return std::make_tuple(projection ? box_iou(*projection, ms[id].box) : 0.0, id == judge.pose_measurement,
                                 ms[id].pose.has_value(), ms[id].score);
        };
        const int keep = *std::max_element(ids.begin(), ids.end(), [&](int a, int b) { return rank(a) < rank(b); });
        for (int id : ids)
          if (id != keep) off.insert(id);
      }
      return off;
    };
    std::set<int> off = losers(l);
    if (off.empty()) continue;
    ObjectLandmark kept = l;
    const auto keep_all_but_off = [&]() {
      kept.measurements.clear();
      for (int id : l.measurements)
        if (!off.count(id)) kept.measurements.push_back(id);
    };
    // A pose measurement that leaves made the projection it was judged by: the landmark is placed
    // from the others and the keyframes judged again, until its pose measurement stays.
    for (int round = 0; round < 3 && off.count(kept.pose_measurement); ++round) {
      keep_all_but_off();
      if (std::none_of(kept.measurements.begin(), kept.measurements.end(), [&](int id) { return ms[id].pose.has_value(); }))
        break;  // nothing left to place it by
      place(kept);
      off = losers(kept);
    }
    if (off.count(kept.pose_measurement)) continue;  // no stable choice: left as it is
    keep_all_but_off();
    removed += static_cast<int>(off.size());
    l = std::move(kept);
  }
  return removed;
}

void drop_landmarks_inside_other_classes(std::vector<ObjectLandmark>& landmarks,
                                         const std::set<std::string>& support_classes) {
  // Each landmark is tested against the stronger ones that are still kept.
  const std::vector<size_t> order = strongest_first(landmarks);
  std::vector<bool> gone(landmarks.size(), false);
  for (size_t oi = 1; oi < order.size(); ++oi) {
    const ObjectLandmark& weak = landmarks[order[oi]];
    if (support_classes.count(weak.label)) continue;
    for (size_t si = 0; si < oi && !gone[order[oi]]; ++si) {
      const ObjectLandmark& strong = landmarks[order[si]];
      gone[order[oi]] = !gone[order[si]] && strong.label != weak.label && !support_classes.count(strong.label) &&
                        strong.measurements.size() > weak.measurements.size() &&
                        inside_box(strong.pose, weak.pose.pose.translation(), true);
    }
  }
  erase_gone(landmarks, gone);
}

namespace {

// Splits one MOT track (measurement ids in keyframe order) where its 3-D positions disagree: each
// placed measurement joins the segment whose mean position is nearest within split_distance, or
// starts a new one; unplaced measurements stay with the latest segment.
std::vector<std::vector<int>> split_track_by_position(const std::vector<int>& ids, const std::vector<ObjectMeasurement>& ms,
                                                      double split_distance) {
  std::vector<std::vector<int>> segments;
  std::vector<Eigen::Vector3d> sums;
  std::vector<int> counts;
  int latest = -1;
  for (int id : ids) {
    if (!ms[id].pose) {
      if (latest < 0) {
        segments.emplace_back();
        sums.emplace_back(Eigen::Vector3d::Zero());
        counts.push_back(0);
        latest = static_cast<int>(segments.size()) - 1;
      }
      segments[latest].push_back(id);
      continue;
    }
    const Eigen::Vector3d p = ms[id].pose->pose.translation();
    int best = -1;
    double best_d = split_distance;
    for (size_t s = 0; s < segments.size(); ++s) {
      if (counts[s] == 0) continue;
      const double d = (sums[s] / counts[s] - p).norm();
      if (d <= best_d) best_d = d, best = static_cast<int>(s);
    }
    if (best < 0) {
      // An unplaced-only segment adopts its first placed measurement.
      if (latest >= 0 && counts[latest] == 0) best = latest;
      else {
        segments.emplace_back();
        sums.emplace_back(Eigen::Vector3d::Zero());
        counts.push_back(0);
        best = static_cast<int>(segments.size()) - 1;
      }
    }
    segments[best].push_back(id);
    sums[best] += p;
    ++counts[best];
    latest = best;
  }
  return segments;
}

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace

std::vector<std::pair<int, int>> track_in_group(const std::vector<int>& group_keyframes,
                                                const std::vector<std::vector<int>>& by_keyframe,
                                                const std::vector<ObjectMeasurement>& measurements,
                                                const mot::TrackerOptions& options, const KeyframeViews* views,
                                                double min_appearance_width) {
  mot::Tracker tracker(options);
  std::map<std::string, int> classes;
  std::vector<std::pair<int, int>> out;  // (measurement id, track id)
  // Per track: a world point on its last box's centre ray, at the depth of its last measured pose
  // (the ray's depth is kept when a later box has no pose), and that box's size and depth. A track
  // of side-cut boxes alone is predicted from their latest side-cut pose instead: its 3-D box's
  // image box, cut by the image as the detections are, or out of view (so a chair leaving the view
  // at a side border is not left there for the next chair to reach, and one entering grows).
  struct Anchor {
    Eigen::Vector3d p_world;
    double width = 0, height = 0, depth = 0;
    std::optional<ObjectPose> side_cut;  // the 3-D box of a side-cut box measured as if uncut
  };
  std::map<int, Anchor> anchors;
  const auto known = [&](int kf) { return views && kf >= 0 && kf < static_cast<int>(views->T_wc.size()); };
  for (int kf : group_keyframes) {
    if (kf < 0 || kf >= static_cast<int>(by_keyframe.size())) continue;
    mot::Tracker::BoxPredictor predict;
    slam::SE3 T_cw;
    if (known(kf)) {
      T_cw = views->T_wc[kf].inverse();
      predict = [&](const mot::Track& t) -> std::optional<Eigen::Vector4d> {
        const auto a = anchors.find(t.id);
        if (a == anchors.end()) return std::nullopt;
        if (a->second.side_cut)  // its image box, cut by the image as a detection is
          if (const auto box = projected_box(*a->second.side_cut, *views, kf)) return box;
        const Eigen::Vector3d pc = T_cw * a->second.p_world;
        if (pc.z() < 0.1) return std::nullopt;
        const Eigen::Vector2d c = views->camera.project(pc);
        const double k = a->second.depth / pc.z(), hw = 0.5 * k * a->second.width, hh = 0.5 * k * a->second.height;
        return Eigen::Vector4d(c.x() - hw, c.y() - hh, c.x() + hw, c.y() + hh);
      };
    }
    std::vector<mot::Detection> dets;
    for (int id : by_keyframe[kf]) {
      const ObjectMeasurement& m = measurements[id];
      mot::Detection d;
      d.box = m.box;
      d.class_id = class_index(m.label, classes);
      d.score = m.score;
      if (m.box(2) - m.box(0) >= min_appearance_width) d.embedding = m.embedding;
      d.user_index = id;
      dets.push_back(std::move(d));
    }
    const std::vector<int> tracks = tracker.update(dets, 1.0, predict);
    for (size_t i = 0; i < dets.size(); ++i) out.emplace_back(dets[i].user_index, tracks[i]);
    if (!known(kf)) continue;
    for (size_t i = 0; i < dets.size(); ++i) {
      if (tracks[i] < 0) continue;
      const ObjectMeasurement& m = measurements[dets[i].user_index];
      const auto a = anchors.find(tracks[i]);
      // A track of side-cut boxes alone follows their latest side-cut pose.
      const bool side_cut_only = !m.pose && m.side_cut_pose && (a == anchors.end() || a->second.side_cut);
      double depth = 0;
      if (m.pose) depth = (T_cw * m.pose->pose.translation()).z();
      else if (side_cut_only)
        depth = (T_cw * m.side_cut_pose->pose.translation()).z();
      else if (a != anchors.end()) depth = (T_cw * a->second.p_world).z();
      if (!(depth > 0.1)) continue;
      const Eigen::Vector2d centre(0.5 * (m.box(0) + m.box(2)), 0.5 * (m.box(1) + m.box(3)));
      anchors[tracks[i]] = Anchor{views->T_wc[kf] * (views->camera.unproject(centre) * depth), m.box(2) - m.box(0),
                                  m.box(3) - m.box(1), depth, side_cut_only ? m.side_cut_pose : std::nullopt};
    }
  }
  return out;
}

AssociationResult associate_objects(const std::vector<ObjectMeasurement>& ms, const std::vector<std::vector<int>>& groups,
                                    const SemanticOptions& options, const KeyframeViews* views) {
  const bool hdp_only = options.association.mode == "hdp-only";
  AssociationResult r;
  r.landmark_of.assign(ms.size(), -1);
  r.track_of.assign(ms.size(), -1);
  r.group_of.assign(ms.size(), -1);
  int max_kf = -1;
  for (const auto& m : ms) max_kf = std::max(max_kf, m.keyframe);
  std::vector<std::vector<int>> by_keyframe(max_kf + 1);
  for (const auto& m : ms) by_keyframe[m.keyframe].push_back(m.id);

  // Level 1: group objects.
  auto t0 = std::chrono::steady_clock::now();
  std::vector<GroupObject> objects;
  std::vector<std::vector<int>> items;  // per CRF group: object indices
  std::vector<std::vector<int>> unplaced;  // group objects without a placed measurement
  std::vector<std::string> unplaced_labels;
  if (hdp_only) {
    for (int kf = 0; kf <= max_kf; ++kf) {
      if (by_keyframe[kf].empty()) continue;
      std::vector<int> g;
      for (int id : by_keyframe[kf]) {
        if (!ms[id].pose) continue;  // HDP-SLAM needs the measurement's pose
        r.group_of[id] = static_cast<int>(items.size());
        g.push_back(static_cast<int>(objects.size()));
        objects.push_back(make_group_object(static_cast<int>(items.size()), {id}, ms));
      }
      if (!g.empty()) items.push_back(std::move(g));
    }
  } else {
    for (size_t n = 0; n < groups.size(); ++n) {
      std::map<int, std::vector<int>> tracks;
      for (const auto& [id, track] :
           track_in_group(groups[n], by_keyframe, ms, options.tracker, options.groups.camera_motion ? views : nullptr,
                          options.groups.min_appearance_width)) {
        r.track_of[id] = track;
        r.group_of[id] = static_cast<int>(n);
        if (track >= 0) tracks[track].push_back(id);
      }
      std::vector<int> g;
      for (const auto& [track, ids] : tracks)
        for (const auto& segment : split_track_by_position(ids, ms, options.groups.split_distance)) {
          GroupObject o = make_group_object(static_cast<int>(items.size()), segment, ms);
          if (o.features.empty()) {  // no measurement could be placed: not an HDP item
            unplaced.push_back(o.measurements);
            unplaced_labels.push_back(o.label);
            continue;
          }
          g.push_back(static_cast<int>(objects.size()));
          objects.push_back(std::move(o));
        }
      items.push_back(std::move(g));  // may be empty: the sampler handles empty groups
    }
  }
  r.mot_seconds = seconds_since(t0);
  r.num_group_objects = static_cast<int>(objects.size());
  r.num_groups = static_cast<int>(items.size());
  if (objects.empty()) return r;

  // Level 2: HDP across groups.
  t0 = std::chrono::steady_clock::now();
  // The sampler's MAP choice scores states without the landmark compactness (suffix swaps only).
  AssociationOptions model_options = options.association;
  model_options.compactness_weight = 0;
  AssociationModel model(objects, items, model_options);
  std::vector<int> sizes;
  for (const auto& g : items) sizes.push_back(static_cast<int>(g.size()));
  hdp::CrfOptions crf = options.association.crf;
  // Distinct landmarks are enforced where they are a fact (AssociationModel::cannot_link: two
  // detections in one keyframe), not for every pair in a group: MOT may cut one track in two.
  crf.cannot_link_within_group = false;
  // Independent chains (seeds seed, seed + 1, ...) on up to association.threads threads; the MAP
  // state of the chain with the highest log p(x, t, k). One chain can stay in a state where two
  // neighbours swap landmarks over a run of groups: one item at a time cannot undo it, as the
  // cannot-link keeps the two apart in every group.
  const int chains = options.association.chains;
  std::vector<hdp::CrfResult> results(static_cast<size_t>(chains));
  std::atomic<int> next{0};
  const auto work = [&]() {
    for (int c; (c = next++) < chains;) {
      hdp::CrfOptions co = crf;
      co.seed = crf.seed + static_cast<std::uint64_t>(c);
      hdp::CrfSampler sampler(model, sizes, co);
      results[static_cast<size_t>(c)] = sampler.run();
    }
  };
  std::vector<std::thread> pool;
  for (int t = 1; t < std::min(chains, options.association.threads); ++t) pool.emplace_back(work);
  work();
  for (auto& t : pool) t.join();
  size_t best = 0;
  for (size_t c = 1; c < results.size(); ++c)
    if (results[c].log_joint > results[best].log_joint) best = c;
  hdp::CrfResult result = std::move(results[best]);
  r.hdp_log_joint = result.log_joint;
  if (options.association.suffix_swaps && !hdp_only) {
    hdp::SuffixSwapOptions so;
    so.min_gain = options.association.suffix_swap_min_gain;
    const AssociationModel swap_model(objects, items, options.association);
    hdp::improve_by_suffix_swaps(swap_model, result.dish, result.num_dishes, so);
  }
  r.hdp_seconds = seconds_since(t0);
  t0 = std::chrono::steady_clock::now();

  // Landmarks: every measurement takes the dish of its largest group object.
  std::vector<std::vector<int>> dish_objects(result.num_dishes);
  for (size_t j = 0; j < items.size(); ++j)
    for (size_t i = 0; i < items[j].size(); ++i) dish_objects[result.dish[j][i]].push_back(items[j][i]);
  std::vector<int> best_size(ms.size(), 0), dish_of(ms.size(), -1);
  for (int k = 0; k < result.num_dishes; ++k)
    for (int o : dish_objects[k])
      for (int id : objects[o].measurements)
        if (static_cast<int>(objects[o].measurements.size()) >= best_size[id]) {
          best_size[id] = static_cast<int>(objects[o].measurements.size());
          dish_of[id] = k;
        }
  // Per measurement: the largest group object (a track, or a segment of one) holding it, placed or
  // not (association.min_track_measurements).
  std::vector<int> track_length = best_size;
  for (const auto& ids : unplaced)
    for (int id : ids) track_length[id] = std::max(track_length[id], static_cast<int>(ids.size()));
  const AssociationOptions& ao = options.association;
  // A landmark none of whose measurements is placed (one made of a track the sampler never saw) is
  // placed by its side-cut measurements (association.border_side_cut_poses).
  const auto placed_count = [&](const std::vector<int>& ids) {
    const auto count = [&](auto has) { return static_cast<int>(std::count_if(ids.begin(), ids.end(), has)); };
    const int placed = count([&](int id) { return ms[id].pose.has_value(); });
    if (placed > 0 || !ao.border_side_cut_poses) return placed;
    return count([&](int id) { return ms[id].side_cut_pose.has_value(); });
  };
  const auto never_measured_together = [&](const std::vector<int>& a, const std::vector<int>& b) {
    return !detected_apart_in_one_keyframe(keyframe_measurements_of(a, ms), keyframe_measurements_of(b, ms));
  };
  std::vector<std::vector<int>> dish_measurements;
  const auto collect_dish_measurements = [&]() {
    dish_measurements.assign(result.num_dishes, {});
    for (const auto& m : ms)
      if (dish_of[m.id] >= 0) dish_measurements[dish_of[m.id]].push_back(m.id);
  };
  collect_dish_measurements();
  std::vector<std::string> dish_labels(result.num_dishes);
  for (int k = 0; k < result.num_dishes; ++k) dish_labels[k] = objects[dish_objects[k].front()].label;
  // Enough measurements, enough of them placed (one at least: a landmark takes a placed one's pose).
  const auto meets = [&](const std::vector<int>& ids, int min_count, int min_placed) {
    return static_cast<int>(ids.size()) >= min_count && placed_count(ids) >= std::max(1, min_placed);
  };
  // Without the side-border minimums; a track holding enough of them (association.min_track_measurements).
  const auto meets_minimums = [&](const std::vector<int>& ids) {
    const auto tracked = [&](int id) { return std::max(1, track_length[id]) >= ao.min_track_measurements; };
    return meets(ids, ao.min_measurements, ao.min_placed_measurements) &&
           (hdp_only || std::any_of(ids.begin(), ids.end(), tracked));
  };
  if (ao.bridge_unplaced_tracks && !hdp_only) {
    std::vector<bool> reportable(result.num_dishes);
    for (int k = 0; k < result.num_dishes; ++k) reportable[k] = meets_minimums(dish_measurements[k]);
    if (link_through_unplaced_tracks(unplaced, unplaced_labels, dish_labels, dish_measurements, reportable,
                                     never_measured_together, dish_of) > 0)
      collect_dish_measurements();
  }

  // Reported landmarks: dishes with enough measurements, enough of them placed.
  std::vector<ObjectLandmark> candidates;
  std::vector<bool> border_only;  // per candidate: reported only through the side-border minimums
  const auto place = [&](ObjectLandmark& l) {
    std::vector<int> ids;
    std::vector<ObjectPose> poses;
    for (int id : l.measurements)
      if (ms[id].pose) {
        ids.push_back(id);
        poses.push_back(*ms[id].pose);
      }
    if (ids.empty() && ao.border_side_cut_poses)
      for (int id : l.measurements)
        if (ms[id].side_cut_pose) {
          ids.push_back(id);
          poses.push_back(*ms[id].side_cut_pose);
        }
    // Assoc. Eq. 4-6, or HDP-SLAM's first measurement.
    const int pick = hdp_only ? 0 : select_landmark_pose(poses, options.pose_selection);
    l.pose_measurement = ids[pick];
    l.pose = poses[pick];
  };
  const auto reportable = [&](const std::vector<int>& ids, const std::string& label) {
    // The general minimums; or, seen mostly at the image's left or right border in one pass, fewer
    // measurements, fewer placed for the thin classes, and no track needed
    // (association.border_min_measurements, border_min_placed_measurements, border_pass_groups).
    if (meets_minimums(ids)) return true;
    if (!views || hdp_only || !mostly_at_side_border(ids, ms, views->camera, ao.border_touch_px) ||
        (ao.border_pass_groups > 0 &&
         most_in_adjacent_groups(ids, r.group_of, ao.border_pass_groups) < ao.border_min_measurements))
      return false;
    const int min_count = std::min(ao.min_measurements, ao.border_min_measurements);
    return meets(ids, min_count,
                 std::min(ao.min_placed_measurements,
                          options.thin_classes.count(label) ? ao.border_min_placed_measurements : min_count));
  };
  for (int k = 0; k < result.num_dishes; ++k) {
    const std::string& label = dish_labels[k];
    if (!reportable(dish_measurements[k], label)) continue;
    ObjectLandmark l;
    l.label = label;
    l.measurements = dish_measurements[k];
    place(l);
    candidates.push_back(std::move(l));
    border_only.push_back(!meets_minimums(dish_measurements[k]));
  }
  // A thin object seen only at a side border never reaches the sampler: its track, held by no
  // landmark, is reported from its side-cut measurements (association.border_side_cut_poses), when
  // it stands on the floor the other thin landmarks stand on, and apart from every landmark of its
  // class never detected beside it in one keyframe. Those boxes are often cut at the bottom too and
  // completed down from their top, which is the object's only where the side cut leaves it in view;
  // a track that passes out of view and back (a chair of a row passed close) may belong to a
  // landmark that its side cuts place 0.3 m off, as far as from the next chair of a row.
  // Not the axis classes: a pole's side cut is a sliver of its base or shaft, measured on the base's
  // top or the wall behind.
  const std::optional<double> floor = floor_height(candidates, options.thin_classes);
  const size_t reported = candidates.size();
  if (ao.border_side_cut_poses && views && !hdp_only && floor)
    for (auto& [label, ids] : tracks_without_landmark(unplaced, unplaced_labels, dish_of)) {
      if (!options.thin_classes.count(label) || options.axis_classes.count(label) ||
          !mostly_at_side_border(ids, ms, views->camera, ao.border_touch_px) || !reportable(ids, label))
        continue;
      ObjectLandmark l;
      l.label = label;
      l.measurements = std::move(ids);
      place(l);
      if (std::abs(bottom_height(l.pose) - *floor) > ao.border_side_cut_floor_tolerance) continue;
      const auto size = options.class_sizes.find(label);
      const double width = size != options.class_sizes.end() ? std::min(size->second[0], size->second[1])
                                                             : std::min(l.pose.size(0), l.pose.size(1));
      if (std::any_of(candidates.begin(), candidates.begin() + static_cast<std::ptrdiff_t>(reported),
                      [&](const ObjectLandmark& o) {
                        return o.label == l.label && horizontal_distance(o.pose, l.pose) < width &&
                               never_measured_together(o.measurements, l.measurements);
                      }))
        continue;
      candidates.push_back(std::move(l));
      border_only.push_back(true);
    }
  if (views)
    drop_border_landmarks_on_others(candidates, border_only, ms, *views, options.association.border_reprojection_iou,
                                    options.association.border_other_classes);
  const auto never_together = [&](const ObjectLandmark& a, const ObjectLandmark& b) {
    return never_measured_together(a.measurements, b.measurements);
  };
  // Two objects detected apart in at least place_apart_min_share of their keyframes: one may be
  // moved apart instead of merged.
  const auto apart = [&](ObjectLandmark& a, ObjectLandmark& b, const FreePose& free) -> ObjectLandmark* {
    if (ao.place_apart_min_share <= 0 ||
        !detected_apart_in_share(keyframe_measurements_of(a.measurements, ms),
                                 keyframe_measurements_of(b.measurements, ms), ao.place_apart_min_share))
      return nullptr;
    return place_apart(a, b, ms, place, ao.min_placed_measurements, free);
  };
  if (options.association.merge_contained && !hdp_only)
    merge_contained_landmarks(candidates, place, never_together, apart);
  if (options.association.drop_inside_other_class && !hdp_only)
    drop_landmarks_inside_other_classes(candidates, options.support_classes);
  // Conflicts are resolved before the projections judge the other keyframes (a landmark placed on
  // the wrong one of two measurements projects off), and again after them.
  if (ao.one_per_keyframe) keep_one_per_keyframe(candidates, ms, views, place);
  if (ao.reproject != "none" && views && !hdp_only) {
    reassign_by_projection(candidates, ms, *views, ao.reproject_min_iou, ao.reproject_margin, ao.reproject == "all");
    if (ao.one_per_keyframe) keep_one_per_keyframe(candidates, ms, views, place);
  }
  // A landmark whose measurements the projections gave to others, down to its pinned pose
  // measurement (a fragment placed 2 m off), or that kept too few, is no longer reported: its last
  // measurements drop.
  {
    std::vector<bool> gone(candidates.size());
    for (size_t i = 0; i < candidates.size(); ++i) gone[i] = !reportable(candidates[i].measurements, candidates[i].label);
    erase_gone(candidates, gone);
  }
  for (auto& l : candidates) {
    l.id = static_cast<int>(r.landmarks.size());
    for (int id : l.measurements) r.landmark_of[id] = l.id;
    r.landmarks.push_back(std::move(l));
  }
  r.pose_selection_seconds = seconds_since(t0);
  return r;
}

}  // namespace wardmap::semantics
