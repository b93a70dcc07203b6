#include "apps/semantic_job.h"

#include <spdlog/spdlog.h>

#include <chrono>
#include <cstdio>
#include <nlohmann/json.hpp>

#include "apps/progress.h"
#include "semantics/detection/detector_factory.h"
#include "semantics/detection/embedder.h"
#include "semantics/detection/model_search.h"
#include "semantics/export/gltf_export.h"
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

SemanticRun run_semantic_job(const SemanticJob& job) {
  auto reader = slam::io::open_sequence(job.sequence);
  const auto& info = reader->info();
  if (!job.keyframes && !info.has_ground_truth)
    throw InputError(job.sequence.string(), "--poses gt needs ground-truth poses, and this sequence has none");

  std::optional<slam::io::Settings> settings;
  if (!job.settings.empty()) settings = slam::io::load_settings(job.settings);
  slam::PinholeCamera camera;
  if (settings) camera = settings->camera.camera;
  else if (info.calibration) camera = *info.calibration;
  else
    throw InputError(job.sequence.string(), "no calibration: the dataset carries none; give --settings (see data/settings/)");
  if (camera.width != info.width || camera.height != info.height)
    throw InputError(settings ? job.settings.string() : info.calibration_source,
                     "calibration is for " + std::to_string(camera.width) + "x" + std::to_string(camera.height) +
                         " images, the sequence's are " + std::to_string(info.width) + "x" + std::to_string(info.height));

  semantics::SemanticOptions options;
  semantics::DetectorOptions det;
  if (settings) {
    options = semantics::load_semantic_options(settings->section("semantics"), job.settings);
    det = semantics::detector_options_from_yaml(settings->section("detection"), job.settings);
  }
  options.association.mode = job.association;
  options.association.crf.seed = job.seed;
  det.kind = job.detector;
  det.noise.seed = job.seed;
  det.models_dir = job.models_dir;
  det.landmark_set = !job.landmark_set.empty() ? job.landmark_set
                     : info.kind == slam::io::DatasetKind::Kitti ? "road"
                                                                 : "indoor";
  if (auto err = det.validate()) throw InputError(job.settings.empty() ? "--detector" : job.settings.string(), *err);
  auto detector = semantics::make_detector(det, job.sequence);
  semantics::SemanticMapper::EmbedFn embed;
  std::shared_ptr<semantics::Embedder> embedder;
  if (job.embedding) {
    embedder = std::make_shared<semantics::Embedder>(semantics::find_embedder_file(job.models_dir));
    embed = [embedder](const cv::Mat& image, const Eigen::Vector4d& box) -> Eigen::VectorXf {
      try {
        return embedder->embed(image, box);
      } catch (const std::invalid_argument&) {
        return {};  // a sliver of a box: no appearance for this measurement
      }
    };
  }

  semantics::SemanticMapper mapper(options, *detector, embed, camera);
  const slam::Trajectory& gt = reader->ground_truth();
  SemanticRun run;
  run.frames = static_cast<int>(reader->size());
  slam::Trajectory trajectory;
  if (job.keyframes) {
    // Keyframes from the SLAM, in its world.
    mapper.set_up(semantics::estimate_up(job.keyframes->poses));
    std::vector<double> times;
    for (size_t i = 0; i < reader->size(); ++i) times.push_back(reader->timestamp(i));
    Progress progress("semantics", job.keyframes->size(), job.progress);
    for (size_t k = 0; k < job.keyframes->size(); ++k) {
      progress.update(k + 1);
      const auto i = slam::io::nearest_within(times, job.keyframes->timestamps[k], 1e-3);
      if (!i) throw InputError(job.sequence.string(), "no frame at keyframe time " + std::to_string(job.keyframes->timestamps[k]));
      const slam::io::Frame f = reader->read(*i);
      mapper.add_keyframe({f.timestamp, f.image, f.depth, job.keyframes->poses[k]});
    }
    progress.finish();
    trajectory = *job.trajectory;
  } else {
    mapper.set_up(semantics::estimate_up(gt.poses));
    semantics::KeyframeSelector selector(options.keyframes);
    Progress progress("semantics", reader->size(), job.progress);
    for (size_t i = 0; i < reader->size(); ++i) {
      progress.update(i + 1);
      const auto& pose = reader->gt_pose(i);
      if (!pose) continue;
      trajectory.push_back(reader->timestamp(i), *pose);
      if (!selector.accept(*pose)) continue;
      const slam::io::Frame f = reader->read(i);
      mapper.add_keyframe({f.timestamp, f.image, f.depth, *pose});
    }
    progress.finish();
  }
  run.result = mapper.build_map();
  run.measurements = mapper.measurements();
  run.keyframes = mapper.keyframes();
  run.times = mapper.times();

  // Object figures when the sequence has object ground truth (synthetic sequences).
  const fs::path truth_file = job.sequence / "objects.json", ann_file = job.sequence / "annotations.jsonl";
  if (fs::exists(truth_file) && fs::exists(ann_file)) {
    std::vector<semantics::MeasurementRecord> records;
    for (const auto& m : run.measurements) {
      semantics::MeasurementRecord r;
      r.keyframe = m.keyframe, r.timestamp = m.timestamp, r.label = m.label, r.box = m.box, r.score = m.score;
      r.track = run.result.track_of[m.id], r.group = run.result.group_of[m.id], r.landmark = run.result.landmark_of[m.id];
      r.gt_instance = m.gt_instance;
      records.push_back(r);
    }
    std::vector<semantics::TrueObject> estimated;
    for (const auto& l : run.result.landmarks) estimated.push_back({l.id, l.label, l.pose});
    // The run's world onto the ground truth's (identity on ground-truth poses; SE(3) for RGB-D SLAM).
    slam::Sim3 align;
    if (job.trajectory && !gt.empty()) {
      const auto pairs = slam::eval::associate(gt, *job.trajectory, {});
      if (pairs.size() >= 3) align = slam::eval::compute_ate(gt, *job.trajectory, pairs, slam::eval::Alignment::SE3).transform;
    }
    run.evaluation = semantics::evaluate_objects(records, estimated, semantics::read_objects_json(truth_file),
                                                 semantics::load_annotations(ann_file), align);
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
    map.up = semantics::estimate_up(gt.poses);
    semantics::write_map_glb(job.out / "map.glb", map);
    const auto& T = run.times;
    json report = {{"sequence", job.sequence.string()}, {"poses", own_run ? "gt" : "slam"}, {"detector", job.detector},
                   {"association", job.association}, {"seed", job.seed}, {"frames", run.frames},
                   {"keyframes", run.keyframes.size()}, {"groups", run.result.num_groups},
                   {"group_objects", run.result.num_group_objects}, {"measurements", run.measurements.size()},
                   {"landmarks", run.result.landmarks.size()},
                   {"timing_seconds", {{"detection_median_per_keyframe", median(T.detection)},
                                       {"embedding_median_per_keyframe", median(T.embedding)},
                                       {"measurement_median_per_keyframe", median(T.measurement)},
                                       {"mot_total", T.mot}, {"hdp_total", T.hdp}, {"pose_selection_total", T.pose_selection}}}};
    std::string md = "# wardmap run\n\n- sequence: `" + job.sequence.string() + "`\n- poses: " + (own_run ? "ground truth" : "SLAM keyframes") + "\n- detector: " +
                     job.detector + "\n- association: " + job.association + "\n- keyframes: " +
                     std::to_string(run.keyframes.size()) + ", groups: " + std::to_string(run.result.num_groups) +
                     ", landmarks: " + std::to_string(run.result.landmarks.size()) + "\n";
    if (run.evaluation) {
      report["objects"] = evaluation_json(*run.evaluation);
      md += "\n## Objects\n\n```\n" + format_object_evaluation(*run.evaluation) + "```\n";
    }
    io::write_file_atomic(job.out / (own_run ? "report.json" : "objects_report.json"), report.dump(2) + "\n");
    io::write_file_atomic(job.out / (own_run ? "report.md" : "objects_report.md"), md);
  }
  return run;
}

}  // namespace wardmap::apps
