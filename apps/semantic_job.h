// The semantic layer run on a sequence with known poses (wardmap run --poses gt, wardmap compare):
// keyframes from the ground truth, detection, embedding, measurement, groups, MOT, HDP, pose
// selection; then the run folder's files and the object figures.
#pragma once

#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "apps/common.h"
#include "semantics/detection/detector_options.h"
#include "semantics/object_association.h"
#include "semantics/object_metrics.h"
#include "semantics/options.h"
#include "semantics/semantic_mapper.h"
#include "slam/core/trajectory.h"
#include "slam/io/sequence.h"
#include "slam/io/settings.h"

namespace wardmap::apps {

class DetectionCache;
struct SemanticSetup;

struct SemanticJob {
  std::filesystem::path sequence;
  slam::io::ReaderOptions reader;     // --format, --first-frame, --frames, ...
  std::filesystem::path settings;     // optional: camera + `semantics` / `detection` sections
  // --set KEY=VALUE, over the settings file's keys (without a file: semantics.* and detection.* only)
  std::vector<slam::io::SettingOverride> settings_overrides;
  std::filesystem::path out;          // run folder; empty: write nothing
  // The flags below, when given, win over the settings' keys; unset (empty), the settings' key
  // decides, and without it the default named.
  // --detector / detection.kind: annotations on a sequence with annotations.jsonl (wardmap synth),
  // else yolox (default_detector_kind).
  std::string detector;
  std::string association;            // --association / semantics.association.mode: hierarchical
  std::string landmark_set;           // --classes / detection.landmark_set: road for KITTI, indoor otherwise
  std::filesystem::path models_dir;   // --models / detection.models_dir
  bool embedding = true;
  // --seed: the Gibbs sampler's and the detector noise's (detection.annotations.seed); unset: the
  // sampler's is 1.
  std::optional<std::uint64_t> seed;
  bool progress = true;
  // With the hierarchical association, also associate the same measurements with the HDP-only
  // baseline (HDP-SLAM) and report both; its map is not written.
  bool baseline = true;
  // From the SLAM: the keyframes to map (camera-to-world) and the run's trajectory (for aligning the
  // objects to the ground truth). Null: keyframes are chosen from the ground truth (--poses gt), and
  // the run folder's trajectory files and report are written too; otherwise only the object files
  // and objects_report.json/md.
  const slam::Trajectory* keyframes = nullptr;
  const slam::Trajectory* trajectory = nullptr;
  // Monocular SLAM: each keyframe's map points in its camera frame (map units), parallel to
  // `keyframes`. Set: objects are measured on these points, with the map brought to metres by the
  // scale the detections give (semantics/monocular_scale.h), never on the sequence's depth images;
  // the objects, the trajectory in map.glb and the evaluation are in that metric frame.
  const std::vector<std::vector<Eigen::Vector3d>>* keyframe_points = nullptr;
  // From the SLAM: its sparse map's points (world frame, map units), drawn in map.glb (in the metric
  // frame of the objects and the trajectory). Null: the map has no points (--poses gt).
  const std::vector<Eigen::Vector3d>* map_points = nullptr;
  // --poses gt: a Ctrl-C / SIGTERM (InterruptScope, set up by the caller) stops after the frame in
  // hand; the objects are mapped on the keyframes so far and written (SemanticRun::interrupted).
  bool interruptible = false;
  // Prepared beforehand (prepare_semantic_job), e.g. to detect keyframes while the SLAM runs.
  // Null: prepared by run_semantic_job.
  SemanticSetup* setup = nullptr;
};

// What a semantic job runs with, from its settings and flags (errors name the file or the flag).
struct SemanticSetup {
  slam::PinholeCamera camera;
  semantics::SemanticOptions options;
  std::unique_ptr<semantics::Detector> detector;
  std::string detector_kind;  // yolox, nanodet or annotations: the job's choice or its default
  std::vector<std::string> settings_notes;  // keys of the settings file that look meant but are not read
  std::unique_ptr<DetectionCache> cache;  // the detector and the embedder, once per image
  ~SemanticSetup();
};

std::unique_ptr<SemanticSetup> prepare_semantic_job(const SemanticJob& job);

// The detector of a job that names none (--detector) and whose settings give no detection.kind:
// annotations when the sequence has annotations.jsonl, else yolox.
std::string default_detector_kind(const std::filesystem::path& sequence);

struct SemanticRun {
  semantics::AssociationResult result;
  std::vector<semantics::ObjectMeasurement> measurements;
  std::vector<semantics::KeyframeRecord> keyframes;
  semantics::StageTimes times;
  std::optional<semantics::ObjectEvaluation> evaluation;  // when the sequence has object ground truth
  // The HDP-only baseline on the same measurements (SemanticJob::baseline with the hierarchical
  // association), and its figures when the sequence has object ground truth.
  std::optional<semantics::AssociationResult> baseline;
  std::optional<semantics::ObjectEvaluation> baseline_evaluation;
  int frames = 0;
  // SemanticJob::interruptible: the signal that stopped the run (0: none) and the frames read by then.
  int interrupted = 0;
  int frames_processed = 0;
  // --poses gt: the keyframe candidates skipped because their frame could not be read.
  UnreadableFrames unreadable;
  // Monocular SLAM: metres per map unit, and how many detections gave it (0: none; no poses then).
  std::optional<double> metric_scale;
  int scale_estimates = 0;
  // With ground truth: the Sim(3) alignment's scale, i.e. true metres over estimated ones (1: exact).
  std::optional<double> alignment_scale;
};

SemanticRun run_semantic_job(const SemanticJob& job);

// One line per figure, for the terminal.
std::string format_object_evaluation(const semantics::ObjectEvaluation& e);

// Landmarks by class, e.g. "bed 2, chair 5, door 4".
std::string format_landmark_counts(const semantics::AssociationResult& r);

// The run's association beside the HDP-only baseline's (SemanticRun::baseline): a table with one
// row per mode (landmarks, and with ground truth accuracy, Object_GT, position error, ID switches)
// and the landmarks by class. Empty without a baseline.
std::string format_baseline_comparison(const SemanticRun& r);

}  // namespace wardmap::apps
