// Object metrics of ../docs/EVALUATION.md: association accuracy, object count against the ground
// truth, landmark position error, and the MOT stage's ID switches and MOTA.
#pragma once

#include <filesystem>
#include <map>
#include <vector>

#include "semantics/detection/annotations_detector.h"
#include "semantics/object_map_io.h"
#include "slam/core/sim3.h"

namespace wardmap::semantics {

// annotations.jsonl of a synthetic sequence (read by the annotations detector's reader), by timestamp.
using Annotations = std::map<double, std::vector<AnnotatedObject>>;
Annotations load_annotations(const std::filesystem::path& file);
// The annotations of the frame at time t (within 1e-4 s); null when none.
const std::vector<AnnotatedObject>* annotations_at(const Annotations& a, double t);
// Leaves out the frames outside [first, last] (within 1e-4 s): a run on a stretch of the sequence
// (--first-frame, --frames) is scored on the objects seen in that stretch.
void keep_annotations_between(Annotations& a, double first, double last);

struct ObjectEvalOptions {
  double iou_threshold = 0.5;      // box match when measurements carry no true identity
  double seen_min_visible = 0.25;  // a true object counts as seen (Object_GT) when visible at least
  int seen_min_frames = 3;         // this much in at least this many frames
  double mot_min_visible = 0.25;   // MOTA: true objects this visible in a keyframe count as present
};

struct LandmarkMatch {
  int landmark = -1, object = -1;
  int shared = 0;
  double position_error = 0;
};

struct ObjectEvaluation {
  int measurements = 0;
  int identified = 0;        // measurements with a true identity
  int false_positives = 0;   // measurements with none
  int dropped = 0;           // identified measurements assigned to no reported landmark
  int correct = 0;           // identified, assigned, and their landmark is matched to their object
  double association_accuracy = 0;  // % correct / (identified - dropped)
  int landmarks = 0;
  int objects_seen = 0;      // Object_GT
  int objects_mapped = 0;    // true objects matched to a landmark
  double position_error_mean = 0, position_error_max = 0;
  int id_switches = 0;
  double mota = 0;
  std::vector<LandmarkMatch> matches;
};

// `alignment` maps the run's world onto the ground truth's (identity for --poses gt runs).
ObjectEvaluation evaluate_objects(const std::vector<MeasurementRecord>& measurements, const std::vector<TrueObject>& landmarks,
                                  const std::vector<TrueObject>& truth, const Annotations& annotations,
                                  const slam::Sim3& alignment, const ObjectEvalOptions& options = {});

// Area shared by two boxes (x0 y0 x1 y1; 0 when they do not overlap), and intersection over union.
double box_intersection(const Eigen::Vector4d& a, const Eigen::Vector4d& b);
double box_iou(const Eigen::Vector4d& a, const Eigen::Vector4d& b);

}  // namespace wardmap::semantics
