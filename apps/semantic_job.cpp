#include "apps/semantic_job.h"

#include <spdlog/spdlog.h>

#include <chrono>
#include <cstdio>
#include <map>
#include <nlohmann/json.hpp>
#include <utility>

#include "apps/common.h"
#include "apps/detection_cache.h"
#include "apps/interrupt.h"
#include "apps/progress.h"
#include "semantics/detection/detector_factory.h"
#include "semantics/detection/embedder.h"
#include "semantics/detection/model_search.h"
#include "semantics/export/gltf_export.h"
#include "semantics/monocular_scale.h"
#include "semantics/object_map_io.h"
#include "slam/core/errors.h"
#include "slam/eval/trajectory_eval.h"
#include "slam/io/sequence.h"
#include "slam/io/settings.h"
#include "slam/io/text_file.h"
#include "slam/io/trajectory_io.h"

namespace wardmap::apps {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

double median(std::vector<double> v) {
  if (v.empty()) return 0;
  std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
  return v[v.size() / 2];
}

json evaluation_json(const semantics::ObjectEvaluation& e) {
  return {{"association_accuracy", e.association_accuracy}, {"measurements", e.measurements},
          {"identified", e.identified}, {"false_positives", e.false_positives}, {"dropped", e.dropped},
          {"landmarks", e.landmarks}, {"objects_seen", e.objects_seen}, {"objects_mapped", e.objects_mapped},
          {"position_error_mean", e.position_error_mean}, {"position_error_max", e.position_error_max},
          {"id_switches", e.id_switches}, {"mota", e.mota}};
}

// Landmarks by class, in class order.
std::map<std::string, int> landmark_counts(const semantics::AssociationResult& r) {
  std::map<std::string, int> n;
  for (const auto& l : r.landmarks) ++n[l.label];
  return n;
}

}  // namespace

std::string format_object_evaluation(const semantics::ObjectEvaluation& e) {
  char buf[1024];
  std::snprintf(buf, sizeof buf,
                "association accuracy: %.2f %% (%d of %d assigned measurements; %d dropped, %d false positives)\n"
                "objects:              %d landmarks, %d true objects seen, %d mapped\n"
                "position error:       mean %.3f m, max %.3f m\n"
                "MOT in groups:        %d ID switches, MOTA %.3f\n",
                e.association_accuracy, e.correct, e.identified - e.dropped, e.dropped, e.false_positives, e.landmarks,
                e.objects_seen, e.objects_mapped, e.position_error_mean, e.position_error_max, e.id_switches, e.mota);
  return buf;
}

std::string format_landmark_counts(const semantics::AssociationResult& r) {
  std::string out;
  for (const auto& [label, count] : landmark_counts(r)) out += (out.empty() ? "" : ", ") + label + " " + std::to_string(count);
  return out.empty() ? "none" : out;
}

std::string format_baseline_comparison(const SemanticRun& r) {
  if (!r.baseline) return {};
  const bool truth = r.evaluation && r.baseline_evaluation;
  char line[256];
  std::string out;
  if (truth) {
    std::snprintf(line, sizeof line, "%-12s | %9s | %9s | %9s | %8s | %8s | %6s\n", "association", "landmarks",
                  "accuracy", "Object_GT", "pos.err", "max err", "ID sw.");
    out += line;
    for (const auto& [mode, e] : {std::pair{"hierarchical", &*r.evaluation}, std::pair{"hdp-only", &*r.baseline_evaluation}}) {
      std::snprintf(line, sizeof line, "%-12s | %9d | %8.2f%% | %9d | %6.3f m | %6.3f m | %6d\n", mode, e->landmarks,
                    e->association_accuracy, e->objects_seen, e->position_error_mean, e->position_error_max,
                    e->id_switches);
      out += line;
    }
  } else {
    std::snprintf(line, sizeof line, "%-12s | %9s\n%-12s | %9zu\n%-12s | %9zu\n", "association", "landmarks",
                  "hierarchical", r.result.landmarks.size(), "hdp-only", r.baseline->landmarks.size());
    out += line;
  }
  out += "by class: hierarchical " + format_landmark_counts(r.result) + "; hdp-only " +
         format_landmark_counts(*r.baseline) + "\n";
  return out;
}

SemanticSetup::~SemanticSetup() = default;  // DetectionCache is complete here

namespace {

// Whether the settings (file and --set) give the key at this path.
bool settings_give(const YAML::Node& root, std::initializer_list<const char*> path) {
  YAML::Node node;
  node.reset(root);  // not operator=, which would assign to root's node
  for (const char* key : path) {
    if (!node.IsMap()) return false;
    const YAML::Node child = std::as_const(node)[key];
    if (!child) return false;
    node.reset(child);
  }
  return true;
}

}  // namespace

std::unique_ptr<SemanticSetup> prepare_semantic_job(const SemanticJob& job) {
  auto reader = slam::io::open_sequence(job.sequence, job.reader);
  const auto& info = reader->info();
  auto setup = std::make_unique<SemanticSetup>();
  std::optional<slam::io::Settings> settings;
  if (!job.settings.empty())
    slam::io::blame_overrides(job.settings_overrides,
                              [&] { settings = slam::io::load_settings(job.settings, job.settings_overrides); });
  if (settings) {
    slam::io::fit_settings_to_sequence(*settings, info, job.settings_overrides);
    // As a SLAM run does: the settings' depth factor over the format's (noted when they differ).
    if (settings->camera.depth_map_factor) reader->set_depth_factor(*settings->camera.depth_map_factor);
    warn_settings_notes(*settings);
    setup->settings_notes = settings->notes;
  }
  // The semantics and detection sections: the file's, else those --set alone gives (the camera is
  // then the dataset's, so only those sections' keys may be set).
  YAML::Node sections = settings ? settings->root : YAML::Node(YAML::NodeType::Map);
  if (!settings) {
    for (const auto& o : job.settings_overrides)
      if (o.key.rfind("semantics.", 0) != 0 && o.key.rfind("detection.", 0) != 0)
        throw InputError("--set", "'" + o.key + "': without --settings, only semantics.* and detection.* keys can be set");
    slam::io::apply_setting_overrides(sections, job.settings_overrides);
  }
  const fs::path sections_file = settings ? job.settings : fs::path(job.settings_overrides.empty() ? "" : "--set");
  slam::PinholeCamera& camera = setup->camera;
  if (settings) camera = settings->camera.camera;
  else if (info.calibration) camera = *info.calibration;
  else
    throw InputError(job.sequence.string(),
                     "no calibration: the dataset carries none; give --settings (see data/settings/)" +
                         enclosing_dataset_note(job.sequence));

  semantics::SemanticOptions& options = setup->options;
  semantics::DetectorOptions det;
  if (!sections_file.empty()) {
    const YAML::Node& doc = sections;
    slam::io::blame_overrides(job.settings_overrides, [&] {
      options = semantics::load_semantic_options(doc["semantics"], sections_file);
      det = semantics::detector_options_from_yaml(doc["detection"], sections_file);
    });
  }
  // A flag over the settings' key; without either, a default that depends on the sequence.
  if (!job.association.empty()) options.association.mode = job.association;
  if (job.seed) options.association.crf.seed = det.noise.seed = *job.seed;
  if (!job.detector.empty()) det.kind = job.detector;
  else if (!settings_give(sections, {"detection", "kind"})) det.kind = default_detector_kind(job.sequence);
  if (!job.landmark_set.empty()) det.landmark_set = job.landmark_set;
  else if (!settings_give(sections, {"detection", "landmark_set"}))
    det.landmark_set = info.kind == slam::io::DatasetKind::Kitti ? "road" : "indoor";
  if (!job.models_dir.empty()) det.models_dir = job.models_dir;
  setup->detector_kind = det.kind;
  spdlog::info("detector: {}, classes: {}, association: {}", det.kind, det.landmark_set, options.association.mode);
  if (auto err = det.validate()) throw InputError(sections_file.empty() ? "--detector" : sections_file.string(), *err);
  setup->detector = semantics::make_detector(det, job.sequence);
  semantics::SemanticMapper::EmbedFn embed;
  if (job.embedding) {
    auto embedder = std::make_shared<semantics::Embedder>(semantics::find_embedder_file(det.models_dir), det.embedding_threads);
    // A sliver of a box gets an empty embedding: no appearance for that measurement.
    embed = [embedder](const cv::Mat& image, const std::vector<Eigen::Vector4d>& boxes) {
      return embedder->embed_all(image, boxes);
    };
  }
  setup->cache = std::make_unique<DetectionCache>(*setup->detector, std::move(embed));
  return setup;
}

std::string default_detector_kind(const fs::path& sequence) {
  return fs::exists(sequence / "annotations.jsonl") ? "annotations" : "yolox";
}

SemanticRun run_semantic_job(const SemanticJob& job) {
  auto reader = slam::io::open_sequence(job.sequence, job.reader);
  const auto& info = reader->info();
  if (!job.keyframes && !info.has_ground_truth)
    throw InputError(job.sequence.string(),
                     "--poses gt needs ground-truth poses, and this sequence has none" +
                         (info.ground_truth_unmatched.empty() ? "" : ": " + info.ground_truth_unmatched) +
                         enclosing_dataset_note(job.sequence));
  if (!job.keyframes && !info.has_depth)  // every measurement would go without a pose
    throw InputError(job.sequence.string(),
                     "--poses gt measures objects from depth images, and this sequence has none "
                     "(monocular: --poses slam --mode mono --objects)" +
                         enclosing_dataset_note(job.sequence));
  std::unique_ptr<SemanticSetup> own_setup;
  SemanticSetup* setup = job.setup;
  if (!setup) setup = (own_setup = prepare_semantic_job(job)).get();
  setup->cache->finish();  // the images queued while the SLAM ran are all detected
  const slam::PinholeCamera& camera = setup->camera;
  semantics::SemanticOptions options = setup->options;
  DetectionCache& cache = *setup->cache;
  if (job.keyframe_points) options.measurement = semantics::sparse_measurement_options(options);
  semantics::SemanticMapper mapper(options, cache, cache.embed_fn(), camera);
  const slam::Trajectory& gt = reader->ground_truth();
  SemanticRun run;
  run.frames = static_cast<int>(reader->size());
  slam::Trajectory trajectory;
  std::vector<Eigen::Vector3d> map_points;  // for map.glb, in the frame of `trajectory`
  // The world's up, from the cameras whose poses place the objects: the SLAM's keyframes, in the
  // SLAM's world (its first camera's frame), or the ground truth's. map.glb is turned by the same.
  const Eigen::Vector3d up = semantics::estimate_up(job.keyframes ? job.keyframes->poses : gt.poses);
  mapper.set_up(up);
  if (job.keyframes) {
    // Keyframes from the SLAM, in its world.
    std::vector<double> times;
    for (size_t i = 0; i < reader->size(); ++i) times.push_back(reader->timestamp(i));
    const auto frame_of = [&](size_t k) {
      const auto i = slam::io::nearest_within(times, job.keyframes->timestamps[k], 1e-3);
      if (!i) throw InputError(job.sequence.string(), "no frame at keyframe time " + std::to_string(job.keyframes->timestamps[k]));
      return reader->read(*i);
    };
    const auto* points = job.keyframe_points;
    if (points) reader->set_decode_depth(false);  // monocular: measured on map points, never on depth images
    if (points && points->size() != job.keyframes->size())
      throw std::logic_error("run_semantic_job: keyframe_points must be parallel to keyframes");
    double scale = 1;
    if (points) {
      // Monocular: the scale from the scale-class detections first (their detections are kept for the map).
      std::vector<double> estimates;
      Progress progress("object scale", job.keyframes->size(), job.progress);
      for (size_t k = 0; k < job.keyframes->size(); ++k) {
        progress.update(k + 1);
        const slam::io::Frame f = frame_of(k);
        std::vector<Eigen::Vector4d> boxes;
        std::vector<std::string> labels;
        for (const auto& d : cache.detect(f.image, f.timestamp)) boxes.push_back(d.box), labels.push_back(d.label);
        for (double e : semantics::keyframe_scale_estimates((*points)[k], camera, boxes, labels, options))
          estimates.push_back(e);
      }
      progress.finish();
      run.scale_estimates = static_cast<int>(estimates.size());
      run.metric_scale = semantics::metric_scale(estimates, options.monocular);
      if (run.metric_scale) {
        scale = *run.metric_scale;
        spdlog::info("monocular objects: {:.4f} m per map unit (median of {} detections of scale classes)", scale, estimates.size());
      } else {
        spdlog::warn("monocular objects: only {} detections of scale classes (semantics.monocular.scale_classes) with map "
                     "points, {} needed for a metric scale; "
                     "objects get no pose", estimates.size(), options.monocular.min_scale_estimates);
      }
    }
    const auto to_metric = [scale, points](const slam::SE3& T) {
      return points ? slam::SE3(T.rotation(), T.translation() * scale) : T;
    };
    Progress progress("semantics", job.keyframes->size(), job.progress);
    for (size_t k = 0; k < job.keyframes->size(); ++k) {
      progress.update(k + 1);
      const slam::io::Frame f = frame_of(k);
      cv::Mat depth = f.depth;
      if (points)
        depth = run.metric_scale ? semantics::sparse_depth_image((*points)[k], camera, options.monocular.point_radius, scale)
                                 : cv::Mat();
      mapper.add_keyframe({f.timestamp, f.image, depth, to_metric(job.keyframes->poses[k])});
    }
    progress.finish();
    for (size_t i = 0; i < job.trajectory->size(); ++i)
      trajectory.push_back(job.trajectory->timestamps[i], to_metric(job.trajectory->poses[i]));
    if (job.map_points)  // in metres as the trajectory is (scale stays 1 unless monocular)
      for (const Eigen::Vector3d& p : *job.map_points) map_points.push_back(scale * p);
  } else {
    semantics::KeyframeSelector selector(options.keyframes);
    Progress progress("semantics", reader->size(), job.progress);
    for (size_t i = 0; i < reader->size(); ++i) {
      if (job.interruptible && (run.interrupted = InterruptScope::requested())) break;
      run.frames_processed = static_cast<int>(i + 1);
      progress.update(i + 1);
      const auto& pose = reader->gt_pose(i);
      if (!pose) continue;
      trajectory.push_back(reader->timestamp(i), *pose);
      const semantics::KeyframeSelector before = selector;
      if (!selector.accept(*pose)) continue;
      slam::io::Frame f;
      try {
        f = reader->read(i);
      } catch (const FrameReadError& e) {  // skipped: the next frame is judged against the last keyframe
        run.unreadable.add(e, reader->timestamp(i));
        selector = before;
        continue;
      }
      mapper.add_keyframe({f.timestamp, f.image, f.depth, *pose});
    }
    progress.finish();
    run.unreadable.warn_summary(job.sequence);
  }
  run.result = mapper.build_map();
  run.measurements = mapper.measurements();
  run.keyframes = mapper.keyframes();
  run.times = mapper.times();
  // The mapper's calls may have been answered from the cache: the time of the real ones.
  run.times.detection = cache.detection_seconds();
  run.times.embedding = cache.embedding_seconds();

  if (job.baseline && options.association.mode == "hierarchical") run.baseline = mapper.build_map("hdp-only");

  // Object figures when the sequence has object ground truth (synthetic sequences).
  const fs::path truth_file = job.sequence / "objects.json", ann_file = job.sequence / "annotations.jsonl";
  if (fs::exists(truth_file) && fs::exists(ann_file)) {
    // The run's world onto the ground truth's (identity on ground-truth poses; SE(3) for RGB-D SLAM).
    slam::Sim3 align;
    if (job.trajectory && !gt.empty()) {
      const auto pairs = slam::eval::associate(gt, trajectory, {});
      // Monocular: Sim(3), as for its trajectory (EVALUATION.md); the metric scale's own error is
      // reported beside it.
      const auto alignment = job.keyframe_points ? slam::eval::Alignment::Sim3 : slam::eval::Alignment::SE3;
      if (pairs.size() >= 3) align = slam::eval::compute_ate(gt, trajectory, pairs, alignment).transform;
      if (pairs.size() >= 3 && job.keyframe_points && run.metric_scale) run.alignment_scale = align.scale();
    }
    const auto truth = semantics::read_objects_json(truth_file);
    auto annotations = semantics::load_annotations(ann_file);
    // The frames read: all, or those before an interruption.
    const size_t last =
        run.interrupted ? static_cast<size_t>(std::max(run.frames_processed, 1) - 1) : reader->size() - 1;
    semantics::keep_annotations_between(annotations, reader->timestamp(0), reader->timestamp(last));
    const auto evaluate = [&](const semantics::AssociationResult& result) {
      std::vector<semantics::MeasurementRecord> records;
      for (const auto& m : run.measurements) {
        semantics::MeasurementRecord r;
        r.keyframe = m.keyframe, r.timestamp = m.timestamp, r.label = m.label, r.box = m.box, r.score = m.score;
        r.track = result.track_of[m.id], r.group = result.group_of[m.id], r.landmark = result.landmark_of[m.id];
        r.gt_instance = m.gt_instance;
        records.push_back(r);
      }
      std::vector<semantics::TrueObject> estimated;
      for (const auto& l : result.landmarks) estimated.push_back({l.id, l.label, l.pose});
      return semantics::evaluate_objects(records, estimated, truth, annotations, align);
    };
    run.evaluation = evaluate(run.result);
    if (run.baseline) run.baseline_evaluation = evaluate(*run.baseline);
  }

  if (!job.out.empty()) {
    namespace io = slam::io;
    const bool own_run = job.keyframes == nullptr;  // else the SLAM writes the trajectory files
    if (own_run) {
      io::write_tum(job.out / "trajectory.txt", trajectory);
      slam::Trajectory kfs;
      for (const auto& k : run.keyframes) kfs.push_back(k.timestamp, k.T_wc);
      io::write_tum(job.out / "keyframes.txt", kfs);
      std::string frames = "timestamp,status,submap\n";
      char line[96];
      for (size_t i = 0; i < trajectory.size(); ++i) {
        std::snprintf(line, sizeof line, "%.6f,ground_truth,0\n", trajectory.timestamps[i]);
        frames += line;
      }
      io::write_file_atomic(job.out / "frames.csv", frames);
    }
    io::write_file_atomic(job.out / "objects.json", semantics::format_objects_json(run.result.landmarks));
    io::write_file_atomic(job.out / "measurements.jsonl", semantics::format_measurements_jsonl(run.measurements, run.result));
    semantics::GltfMapContent map;
    for (const auto& l : run.result.landmarks)
      map.objects.push_back({l.id, l.label, l.pose.pose.translation(), l.pose.pose.rotation(), l.pose.size,
                             static_cast<int>(l.measurements.size())});
    for (const auto& T : trajectory.poses) map.trajectory.push_back(T.translation());
    map.points = std::move(map_points);
    map.up = up;
    semantics::write_map_glb(job.out / "map.glb", map);
    const auto& T = run.times;
    json report = {{"sequence", job.sequence.string()}, {"poses", own_run ? "gt" : "slam"}, {"detector", setup->detector_kind},
                   {"association", options.association.mode}, {"seed", options.association.crf.seed}, {"frames", run.frames},
                   {"keyframes", run.keyframes.size()}, {"groups", run.result.num_groups},
                   {"group_objects", run.result.num_group_objects}, {"measurements", run.measurements.size()},
                   {"landmarks", run.result.landmarks.size()},
                   {"timing_seconds", {{"detection_median_per_keyframe", median(T.detection)},
                                       {"embedding_median_per_keyframe", median(T.embedding)},
                                       {"measurement_median_per_keyframe", median(T.measurement)},
                                       {"mot_total", T.mot}, {"hdp_total", T.hdp}, {"pose_selection_total", T.pose_selection}}}};
    report["first_frame"] = reader->first_frame();  // of the stretch run (--first-frame)
    if (run.interrupted) {
      report["interrupted"] = signal_name(run.interrupted);
      report["frames_processed"] = run.frames_processed;
    }
    report["settings"] = job.settings.string();     // empty: the defaults
    report["settings_overrides"] = overrides_json(job.settings_overrides);
    report["settings_notes"] = setup->settings_notes;
    if (own_run) report["unreadable_frames"] = run.unreadable.to_json();  // a SLAM run's report has its own
    std::string md =
        "# wardmap run\n\n- sequence: `" + job.sequence.string() +
        "`\n- poses: " + (own_run ? "ground truth" : "SLAM keyframes") + "\n- detector: " + setup->detector_kind +
        "\n- association: " + options.association.mode +
        "\n- settings: " + (job.settings.empty() ? std::string("the defaults") : "`" + job.settings.string() + "`") +
        overrides_text(job.settings_overrides) + "\n" + settings_notes_text(setup->settings_notes) +
        (run.unreadable.empty() ? std::string() : "- " + run.unreadable.summary() + ": no keyframe taken there\n") +
        (run.interrupted ? "- interrupted (" + signal_name(run.interrupted) + ") after frame " +
                               std::to_string(run.frames_processed) + " of " + std::to_string(run.frames) +
                               ": the figures below are for those frames\n"
                         : std::string()) +
        "- keyframes: " + std::to_string(run.keyframes.size()) + ", groups: " + std::to_string(run.result.num_groups) +
        ", landmarks: " + std::to_string(run.result.landmarks.size()) + "\n";
    if (!own_run)  // keyframe images queued for detection while the SLAM ran (the rest: after it)
      report["detection_during_slam"] = {{"keyframes_offered", cache.offered()},
                                         {"queue_full", cache.refused()}};
    if (job.keyframe_points) {
      report["monocular_scale"] = {{"metres_per_map_unit", run.metric_scale ? json(*run.metric_scale) : json(nullptr)},
                                   {"estimates", run.scale_estimates}};
      md += "- monocular map scale: " +
            (run.metric_scale ? std::to_string(*run.metric_scale) + " m per map unit" : std::string("none (no poses)")) +
            " from " + std::to_string(run.scale_estimates) + " detections of scale classes\n";
      if (run.alignment_scale) {
        report["monocular_scale"]["ground_truth_over_estimate"] = *run.alignment_scale;
        md += "- ground-truth scale / estimated scale: " + std::to_string(*run.alignment_scale) + "\n";
      }
    }
    report["landmarks_by_class"] = json(landmark_counts(run.result));
    if (run.evaluation) {
      report["objects"] = evaluation_json(*run.evaluation);
      md += "\n## Objects\n\n```\n" + format_object_evaluation(*run.evaluation) + "```\n";
    }
    if (run.baseline) {
      json b = {{"association", "hdp-only"}, {"landmarks", run.baseline->landmarks.size()},
                {"landmarks_by_class", json(landmark_counts(*run.baseline))},
                {"timing_seconds", {{"hdp_total", run.baseline->hdp_seconds}}}};
      if (run.baseline_evaluation) b["objects"] = evaluation_json(*run.baseline_evaluation);
      report["baseline"] = b;
      md += "\n## Against the HDP-only baseline\n\nThe same measurements associated as HDP-SLAM does (every keyframe its own "
            "group, no MOT, a landmark at its first measurement's pose).\n\n```\n" +
            format_baseline_comparison(run) + "```\n";
    }
    io::write_file_atomic(job.out / (own_run ? "report.json" : "objects_report.json"), report.dump(2) + "\n");
    io::write_file_atomic(job.out / (own_run ? "report.md" : "objects_report.md"), md);
  }
  return run;
}

}  // namespace wardmap::apps
