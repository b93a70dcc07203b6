#include "semantics/object_metrics.h"

#include <algorithm>
#include <cmath>
#include <set>

#include "mot/hungarian.h"
#include "mot/mot_metrics.h"

namespace wardmap::semantics {

namespace fs = std::filesystem;

Annotations load_annotations(const fs::path& file) {
  Annotations out;
  for (auto& frame : read_annotations(file)) out[frame.timestamp] = std::move(frame.objects);
  return out;
}

const std::vector<AnnotatedObject>* annotations_at(const Annotations& a, double t) {
  auto it = a.lower_bound(t - 1e-4);
  if (it == a.end() || it->first > t + 1e-4) return nullptr;
  return &it->second;
}

void keep_annotations_between(Annotations& a, double first, double last) {
  a.erase(a.begin(), a.lower_bound(first - 1e-4));
  a.erase(a.upper_bound(last + 1e-4), a.end());
}

double box_intersection(const Eigen::Vector4d& a, const Eigen::Vector4d& b) {
  const double w = std::min(a(2), b(2)) - std::max(a(0), b(0)), h = std::min(a(3), b(3)) - std::max(a(1), b(1));
  return w > 0 && h > 0 ? w * h : 0.0;
}

double box_iou(const Eigen::Vector4d& a, const Eigen::Vector4d& b) {
  const double inter = box_intersection(a, b);
  if (inter <= 0) return 0.0;
  return inter / ((a(2) - a(0)) * (a(3) - a(1)) + (b(2) - b(0)) * (b(3) - b(1)) - inter);
}

namespace {

// True identity of every measurement: its own when the detector knew it, else the greedy IoU match
// (same class, IoU >= threshold) among its frame's annotated boxes.
std::vector<int> identify(const std::vector<MeasurementRecord>& ms, const Annotations& ann, double iou_threshold) {
  std::vector<int> gt(ms.size(), -1);
  std::map<int, std::vector<size_t>> by_keyframe;
  for (size_t i = 0; i < ms.size(); ++i) {
    if (ms[i].gt_instance >= 0) gt[i] = ms[i].gt_instance;
    else by_keyframe[ms[i].keyframe].push_back(i);
  }
  for (const auto& [kf, idx] : by_keyframe) {
    const auto* boxes = annotations_at(ann, ms[idx.front()].timestamp);
    if (!boxes) continue;
    struct Cand { double iou; size_t m; size_t a; };
    std::vector<Cand> cands;
    for (size_t m : idx)
      for (size_t a = 0; a < boxes->size(); ++a)
        if ((*boxes)[a].label == ms[m].label) {
          const double iou = box_iou(ms[m].box, (*boxes)[a].box);
          if (iou >= iou_threshold) cands.push_back({iou, m, a});
        }
    std::sort(cands.begin(), cands.end(), [](const Cand& x, const Cand& y) { return x.iou > y.iou; });
    std::set<size_t> used_m, used_a;
    for (const auto& c : cands) {
      if (used_m.count(c.m) || used_a.count(c.a)) continue;
      used_m.insert(c.m), used_a.insert(c.a);
      gt[c.m] = (*boxes)[c.a].id;
    }
  }
  return gt;
}

}  // namespace

ObjectEvaluation evaluate_objects(const std::vector<MeasurementRecord>& ms, const std::vector<TrueObject>& landmarks,
                                  const std::vector<TrueObject>& truth, const Annotations& ann, const slam::Sim3& align,
                                  const ObjectEvalOptions& o) {
  ObjectEvaluation e;
  e.measurements = static_cast<int>(ms.size());
  e.landmarks = static_cast<int>(landmarks.size());
  const std::vector<int> gt = identify(ms, ann, o.iou_threshold);

  // Landmark <-> object, one to one, maximising shared measurements (Hungarian on -shared).
  std::map<int, int> lm_index, obj_index;
  for (size_t i = 0; i < landmarks.size(); ++i) lm_index[landmarks[i].id] = static_cast<int>(i);
  for (size_t i = 0; i < truth.size(); ++i) obj_index[truth[i].id] = static_cast<int>(i);
  Eigen::MatrixXd shared = Eigen::MatrixXd::Zero(landmarks.size(), truth.size());
  for (size_t i = 0; i < ms.size(); ++i) {
    if (gt[i] < 0) continue;
    ++e.identified;
    const auto l = lm_index.find(ms[i].landmark);
    const auto t = obj_index.find(gt[i]);
    if (l == lm_index.end()) {
      ++e.dropped;
      continue;
    }
    if (t != obj_index.end()) shared(l->second, t->second) += 1;
  }
  e.false_positives = e.measurements - e.identified;
  std::map<int, int> object_of_landmark;  // landmark index -> object index
  if (shared.size() > 0) {
    const mot::Assignment a = mot::solve_assignment(-shared, -0.5);  // only pairs sharing something
    for (const auto& [l, t] : a.matches) {
      object_of_landmark[l] = t;
      LandmarkMatch m;
      m.landmark = landmarks[l].id;
      m.object = truth[t].id;
      m.shared = static_cast<int>(shared(l, t));
      m.position_error = (align * landmarks[l].pose.pose.translation() - truth[t].pose.pose.translation()).norm();
      e.matches.push_back(m);
    }
  }
  for (size_t i = 0; i < ms.size(); ++i) {
    if (gt[i] < 0) continue;
    const auto l = lm_index.find(ms[i].landmark);
    if (l == lm_index.end()) continue;
    const auto t = object_of_landmark.find(l->second);
    if (t != object_of_landmark.end() && truth[t->second].id == gt[i]) ++e.correct;
  }
  const int assigned = e.identified - e.dropped;
  e.association_accuracy = assigned > 0 ? 100.0 * e.correct / assigned : 0.0;
  e.objects_mapped = static_cast<int>(e.matches.size());
  for (const auto& m : e.matches) {
    e.position_error_mean += m.position_error / e.matches.size();
    e.position_error_max = std::max(e.position_error_max, m.position_error);
  }

  // Object_GT: true objects well seen in enough frames.
  std::map<int, int> frames_seen;
  for (const auto& [t, list] : ann)
    for (const auto& a : list)
      if (a.visible >= o.seen_min_visible) ++frames_seen[a.id];
  for (const auto& [id, n] : frames_seen)
    if (n >= o.seen_min_frames) ++e.objects_seen;

  // CLEAR-MOT of the tracks inside each group (a new tracker per group: no switches across groups).
  std::map<int, std::map<int, std::vector<size_t>>> by_group_kf;  // group -> keyframe -> measurements
  for (size_t i = 0; i < ms.size(); ++i)
    if (ms[i].group >= 0) by_group_kf[ms[i].group][ms[i].keyframe].push_back(i);
  for (const auto& [g, kfs] : by_group_kf) {
    mot::ClearMotAccumulator acc;
    for (const auto& [kf, idx] : kfs) {
      mot::FrameCorrespondences f;
      std::set<int> present;
      if (const auto* list = annotations_at(ann, ms[idx.front()].timestamp))
        for (const auto& a : *list)
          if (a.visible >= o.mot_min_visible) present.insert(a.id);
      std::set<int> found;
      for (size_t i : idx) {
        if (ms[i].track < 0) continue;
        if (gt[i] >= 0 && !found.count(gt[i])) {
          f.matches.emplace_back(gt[i], ms[i].track);
          found.insert(gt[i]);
        } else {
          ++f.false_positives;
        }
      }
      for (int id : present)
        if (!found.count(id)) ++f.misses;
      acc.add_frame(f);
    }
    e.id_switches += acc.result().id_switches;
    e.mota += acc.result().mota;  // averaged below
  }
  if (!by_group_kf.empty()) e.mota /= by_group_kf.size();
  return e;
}

}  // namespace wardmap::semantics
