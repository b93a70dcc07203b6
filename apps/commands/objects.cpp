// wardmap eval-objects: object figures of a run folder against a synthetic sequence's ground truth.
// wardmap compare: both association modes on the same sequences, one table (Assoc. Table II).
#include <cstdio>
#include <fstream>
#include <memory>
#include <nlohmann/json.hpp>
#include <utility>

#include "apps/commands/commands.h"
#include "apps/common.h"
#include "apps/compare_summary.h"
#include "apps/semantic_job.h"
#include "slam/core/errors.h"
#include "slam/eval/trajectory_eval.h"
#include "slam/io/sequence.h"
#include "slam/io/text_file.h"
#include "slam/io/trajectory_io.h"

namespace wardmap::apps {

namespace fs = std::filesystem;
using nlohmann::json;

void add_semantic_options(CLI::App* cmd, SemanticJob& job);  // run.cpp

namespace {

// The folder's name, also when given with a trailing slash (a shell completion).
std::string folder_name(const fs::path& path) {
  const fs::path p = path.lexically_normal();
  return (p.has_filename() ? p.filename() : p.parent_path().filename()).string();
}

// A report a run folder holds, or null when it has none (an unparsable one counts as none).
json read_report(const fs::path& file) {
  if (!fs::exists(file)) return json();
  std::ifstream in(file);
  json report = json::parse(in, nullptr, false);
  return report.is_object() ? report : json();
}

void require_object_ground_truth(const fs::path& seq) {
  if (!fs::is_directory(seq)) throw InputError(seq.string(), fs::exists(seq) ? "not a sequence folder" : "not found");
  for (const char* f : {"objects.json", "annotations.jsonl"})
    if (!fs::exists(seq / f)) throw InputError((seq / f).string(), "not found: object ground truth comes from wardmap synth sequences");
}

struct EvalObjectsArgs {
  std::string run, sequence, json, align = "auto";
};

void eval_objects(const EvalObjectsArgs& a) {
  check_output_files({{a.json, "--json"}});
  const fs::path run = a.run, seq = a.sequence;
  require_run_files(run, {"trajectory.txt", "measurements.jsonl", "objects.json"});
  require_object_ground_truth(seq);
  // A run of another sequence would be scored against the wrong objects without a word (the synthetic
  // sequences share their timestamps, so the trajectories still pair up).
  const json report = read_report(run / "report.json");
  if (report.contains("sequence") && report["sequence"].is_string()) {
    const std::string made_on = folder_name(report["sequence"].get<std::string>());
    if (made_on != folder_name(seq))
      throw InputError((run / "report.json").string(),
                       "the run was made on '" + made_on + "', not on '" + folder_name(seq) + "' (--sequence)");
  }
  const bool monocular = report.is_object() && report.value("mode", json()) == "mono";
  // A monocular run's objects are in metres (its metric scale in objects_report.json), its
  // trajectory.txt in map units: the trajectory is brought to metres before the alignment.
  double metres_per_map_unit = 1;
  const json objects_report = read_report(run / "objects_report.json");
  if (objects_report.contains("monocular_scale")) {
    const json& s = objects_report["monocular_scale"];
    if (!s.is_object() || !s.contains("metres_per_map_unit") || !s["metres_per_map_unit"].is_number() ||
        !(s["metres_per_map_unit"].get<double>() > 0))
      throw InputError((run / "objects_report.json").string(),
                       "monocular_scale.metres_per_map_unit is not a positive number: the run placed no objects");
    metres_per_map_unit = s["metres_per_map_unit"].get<double>();
  }
  // The run's world onto the ground truth's, by the trajectory alignment of EVALUATION.md (auto:
  // Sim(3) for a monocular run, SE(3) otherwise, as `wardmap run` scores its own).
  const std::string alignment = a.align != "auto" ? a.align : monocular ? "sim3" : "se3";
  // A run on a stretch of the sequence (--first-frame, --frames) is scored on that stretch.
  slam::io::ReaderOptions stretch;
  if (report.is_object()) {
    const json first = report.value("first_frame", json(0)), frames = report.value("frames", json(0));
    if (!first.is_number_unsigned() || !frames.is_number_unsigned())
      throw InputError((run / "report.json").string(), "first_frame and frames must be frame counts");
    stretch.first_frame = first.get<size_t>();
    stretch.frame_count = frames.get<size_t>();
  }
  auto reader = slam::io::open_sequence(seq, stretch);
  slam::Sim3 align;
  if (alignment != "none") {
    auto est = slam::io::read_trajectory(run / "trajectory.txt");
    for (auto& T : est.poses) T = slam::SE3(T.rotation(), T.translation() * metres_per_map_unit);
    const auto pairs = slam::eval::associate(reader->ground_truth(), est, {});
    align = slam::eval::compute_ate(reader->ground_truth(), est, pairs, slam::eval::parse_alignment(alignment)).transform;
  }
  std::vector<semantics::TrueObject> landmarks = semantics::read_objects_json(run / "objects.json");
  auto annotations = semantics::load_annotations(seq / "annotations.jsonl");
  semantics::keep_annotations_between(annotations, reader->timestamp(0), reader->timestamp(reader->size() - 1));
  const auto e = semantics::evaluate_objects(semantics::read_measurements_jsonl(run / "measurements.jsonl"), landmarks,
                                             semantics::read_objects_json(seq / "objects.json"), annotations, align);
  std::printf("%s", format_object_evaluation(e).c_str());
  if (!a.json.empty()) {
    json j = {{"run", a.run}, {"sequence", a.sequence}, {"association_accuracy", e.association_accuracy},
              {"landmarks", e.landmarks}, {"objects_seen", e.objects_seen}, {"objects_mapped", e.objects_mapped},
              {"position_error_mean", e.position_error_mean}, {"position_error_max", e.position_error_max},
              {"id_switches", e.id_switches}, {"mota", e.mota}, {"dropped", e.dropped},
              {"false_positives", e.false_positives}, {"identified", e.identified}};
    slam::io::write_file_atomic(a.json, j.dump(2) + "\n");
  }
}

struct CompareArgs {
  std::vector<std::string> sequences;
  SemanticJob job;
  ReaderArgs reader;
  std::string json;
  std::vector<std::string> set;  // --set KEY=VALUE
  CompareTargets targets;
};

void compare(CompareArgs& a) {
  check_output_files({{a.json, "--json"}});
  a.job.reader = reader_options(a.reader);
  a.job.settings_overrides = parse_set_options(a.set);
  for (const auto& s : a.sequences) require_object_ground_truth(s);  // before the table starts
  const auto job_for = [&](const std::string& s) {
    // Measured once, associated both ways: the baseline's figures are those of a separate
    // --association hdp-only run (same measurements, same sampler seed).
    SemanticJob job = a.job;
    job.sequence = s;
    job.association = "hierarchical";
    job.baseline = true;
    job.out.clear();
    job.progress = false;
    return job;
  };
  // The settings, --set and the detector are checked before the table starts too: on the first
  // sequence's set-up, which its run then uses.
  std::unique_ptr<SemanticSetup> first_setup = prepare_semantic_job(job_for(a.sequences.front()));
  json rows = json::array();
  std::printf("%-28s | %-12s | %9s | %7s | %9s | %8s | %8s | %7s\n", "sequence", "association", "accuracy", "objects",
              "Object_GT", "pos.err", "max err", "ID sw.");
  std::printf("%s\n", std::string(110, '-').c_str());
  std::vector<CompareRow> summary;
  for (const auto& s : a.sequences) {
    const std::string name = folder_name(s);
    SemanticJob job = job_for(s);
    if (first_setup) job.setup = first_setup.get();
    const SemanticRun r = run_semantic_job(job);
    first_setup.reset();
    if (!r.evaluation || !r.baseline_evaluation)
      throw InputError(s, "no object ground truth (objects.json + annotations.jsonl): use a wardmap synth sequence");
    for (const auto& [mode, e] : {std::pair{"hdp-only", &*r.baseline_evaluation}, std::pair{"hierarchical", &*r.evaluation}}) {
      std::printf("%-28s | %-12s | %8.2f%% | %7d | %9d | %6.3f m | %6.3f m | %7d\n", name.c_str(), mode,
                  e->association_accuracy, e->landmarks, e->objects_seen, e->position_error_mean, e->position_error_max,
                  e->id_switches);
      rows.push_back({{"sequence", s}, {"association", mode}, {"accuracy", e->association_accuracy},
                      {"landmarks", e->landmarks}, {"objects_seen", e->objects_seen},
                      {"position_error_mean", e->position_error_mean}, {"position_error_max", e->position_error_max},
                      {"id_switches", e->id_switches}, {"dropped", e->dropped}, {"identified", e->identified}});
    }
    summary.push_back({name, *r.evaluation, *r.baseline_evaluation});
    std::fflush(stdout);
  }
  std::printf("\n%s", format_compare_summary(summary, a.targets).c_str());
  if (!a.json.empty()) slam::io::write_file_atomic(a.json, rows.dump(2) + "\n");
}

}  // namespace

void add_eval_objects_command(CLI::App& app) {
  auto a = std::make_shared<EvalObjectsArgs>();
  auto* cmd = app.add_subcommand("eval-objects",
                                 "Object figures of a run folder against a synthetic sequence (docs/EVALUATION.md):\n"
                                 "association accuracy, object count, landmark position error, MOT ID switches");
  cmd->add_option("--run", a->run, "Run folder written by wardmap run")->required();
  cmd->add_option("--sequence", a->sequence, "The synthetic sequence the run was made on")->required();
  cmd->add_option("--align", a->align,
                  "Trajectory alignment applied to the landmarks: se3, sim3, none, or auto (sim3 for a monocular\n"
                  "run, whose trajectory is first brought to metres by its objects' metric scale; se3 otherwise)")
      ->capture_default_str()
      ->check(CLI::IsMember({"auto", "se3", "sim3", "none"}));
  cmd->add_option("--json", a->json, "Also write the figures as JSON");
  cmd->callback([a] { eval_objects(*a); });
}

void add_compare_command(CLI::App& app) {
  auto a = std::make_shared<CompareArgs>();
  auto* cmd = app.add_subcommand("compare",
                                 "Run both association modes (hdp-only baseline, hierarchical) on the same synthetic\n"
                                 "sequences with ground-truth poses and print one table, as the paper's Table II");
  cmd->add_option("sequences", a->sequences, "Synthetic sequences (wardmap synth outputs)")->required();
  cmd->add_option("--json", a->json, "Also write the table as JSON");
  cmd->add_option("--min-accuracy", a->targets.min_accuracy,
                  "The summary under the table counts the sequences whose association accuracy (%) is at least this")
      ->capture_default_str()
      ->check(CLI::Range(0.0, 100.0));
  cmd->add_option(
         "--max-position-error", a->targets.max_position_error,
         "The summary under the table counts the sequences whose mean landmark position error (m) is at most this")
      ->capture_default_str()
      ->check(CLI::NonNegativeNumber);
  add_semantic_options(cmd, a->job);
  add_set_option(cmd, a->set, "The same for every sequence; without --settings, semantics.* and detection.* only");
  add_reader_options(cmd, a->reader);
  cmd->callback([a] { compare(*a); });
}

}  // namespace wardmap::apps
