// wardmap run <sequence>: the SLAM front-process (--poses slam, the default), with the semantic layer on
// its keyframes (--objects), or the semantic layer alone on ground-truth poses (--poses gt).
#include <spdlog/spdlog.h>
#include <sys/stat.h>

#include <cstdio>
#include <memory>
#include <optional>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "apps/commands/commands.h"
#include "apps/common.h"
#include "apps/interrupt.h"
#include "apps/semantic_job.h"
#include "apps/slam_job.h"
#include "slam/core/errors.h"
#include "slam/io/text_file.h"

namespace wardmap::apps {

namespace {

struct RunArgs {
  SemanticJob job;
  ReaderArgs reader;
  std::string poses = "slam";
  std::string mode;  // empty: rgbd when the sequence has depth, else mono
  bool deterministic = false;
  bool realtime = false;
  bool objects = false;
  std::filesystem::path vocabulary;
  std::vector<std::string> set;  // --set KEY=VALUE
};

// The run's files (objects.json, trajectory.txt, report.json, ...) must not overwrite a dataset's:
// a synthetic sequence's objects.json is its object ground truth. --out may not be the sequence's
// folder, nor a folder holding another dataset (an image folder only when it is the sequence).
void refuse_out_over_a_dataset(const std::filesystem::path& out, const std::filesystem::path& sequence) {
  std::error_code ec;
  if (!std::filesystem::is_directory(out, ec)) return;
  if (std::filesystem::equivalent(out, sequence, ec))
    throw InputError(out.string(),
                     "--out is the sequence's own folder; the run's files would overwrite the sequence's "
                     "(objects.json, ...): give another folder");
  std::optional<slam::io::DatasetKind> kind;
  try {
    kind = slam::io::detect_dataset_kind(out);
  } catch (const InputError&) {  // not a dataset
  }
  if (kind && *kind != slam::io::DatasetKind::ImageFolder)
    throw InputError(out.string(), "--out holds a dataset (" + slam::io::to_string(*kind) +
                                       " layout); the run's files would overwrite its own: give another folder");
}

// The files a run may write into --out (slam_job.cpp, semantic_job.cpp). Those an earlier run left
// there and this run does not write again (objects.json after a run without --objects, points.ply
// after --poses gt) are removed once this run has written its own, so that the folder never mixes
// two runs (eval-objects would score old objects on a new trajectory). A file counts as written
// again when its inode or time changed: every output is written to a temporary name and renamed.
class EarlierRunFiles {
 public:
  explicit EarlierRunFiles(const std::filesystem::path& out) : out_(out) {
    if (out.empty()) return;
    for (const char* name :
         {"trajectory.txt", "frames.csv", "timing.csv", "keyframes.txt", "points.ply", "report.json", "report.md",
          "objects.json", "measurements.jsonl", "map.glb", "objects_report.json", "objects_report.md"})
      if (const auto id = identity(out / name)) found_.emplace_back(name, *id);
  }
  void remove_those_not_written_again() const {
    std::string removed;
    for (const auto& [name, id] : found_) {
      std::error_code ec;
      if (identity(out_ / name) == id && std::filesystem::remove(out_ / name, ec))
        removed += (removed.empty() ? "" : ", ") + name;
    }
    if (!removed.empty())
      spdlog::info("{}: removed {} of an earlier run, which this run does not write", out_.string(), removed);
  }

 private:
  using Identity = std::tuple<dev_t, ino_t, long, long>;  // device, inode, modification time (s, ns)
  static std::optional<Identity> identity(const std::filesystem::path& file) {
    struct stat st {};
    if (::stat(file.c_str(), &st) != 0) return std::nullopt;
    return Identity{st.st_dev, st.st_ino, st.st_mtim.tv_sec, st.st_mtim.tv_nsec};
  }
  std::filesystem::path out_;
  std::vector<std::pair<std::string, Identity>> found_;
};

void run(RunArgs& a) {
  a.job.reader = reader_options(a.reader);
  a.job.settings_overrides = parse_set_options(a.set);
  // Checked before the run, not when its outputs are written at the end.
  if (!a.job.out.empty()) {
    slam::io::check_output_folder(a.job.out, "--out");
    refuse_out_over_a_dataset(a.job.out, a.job.sequence);
  }
  const EarlierRunFiles earlier(a.job.out);
  if (a.poses == "slam") {
    spdlog::info("run: {} (SLAM front-process{})", a.job.sequence.string(), a.mode.empty() ? "" : ", " + a.mode);
    SlamJob s{a.job.sequence, a.job.settings, a.job.out, a.mode, a.job.progress, a.deterministic, a.vocabulary,
              a.objects ? &a.job : nullptr};
    s.realtime = a.realtime;
    s.settings_overrides = a.job.settings_overrides;
    s.reader = a.job.reader;
    run_slam_job(s);
    earlier.remove_those_not_written_again();
    return;
  }
  if (a.mode == "mono")
    throw InputError(a.job.sequence.string(), "--poses gt measures objects from depth: use --mode rgbd on a sequence with depth");
  // Before the start is logged: a signal after it (the tests send one) meets the handlers.
  std::optional<InterruptScope> interrupt_scope(std::in_place);
  spdlog::info("run: {} (poses: ground truth)", a.job.sequence.string());
  a.job.interruptible = true;
  const SemanticRun r = run_semantic_job(a.job);
  interrupt_scope.reset();
  earlier.remove_those_not_written_again();
  std::printf("frames %d, keyframes %zu, groups %d, group objects %d, measurements %zu, landmarks %zu\n", r.frames,
              r.keyframes.size(), r.result.num_groups, r.result.num_group_objects, r.measurements.size(),
              r.result.landmarks.size());
  std::printf("objects by class: %s\n", format_landmark_counts(r.result).c_str());
  if (r.evaluation) std::printf("%s", format_object_evaluation(*r.evaluation).c_str());
  if (r.baseline) std::printf("against the HDP-only baseline:\n%s", format_baseline_comparison(r).c_str());
  if (!a.job.out.empty()) std::printf("outputs in %s\n", a.job.out.c_str());
  if (r.interrupted)
    throw Interrupted(r.interrupted, "interrupted (" + signal_name(r.interrupted) + ") after frame " +
                                         std::to_string(r.frames_processed) + " of " + std::to_string(r.frames) +
                                         "; the objects are those of its keyframes");
}

}  // namespace

void add_semantic_options(CLI::App* cmd, SemanticJob& job) {
  cmd->add_option("--settings", job.settings, "Settings YAML: camera (ORB-SLAM3 keys) and the semantics/detection sections");
  cmd->add_option("--detector", job.detector,
                  "Object detector: annotations (a wardmap synth sequence's boxes, with noise), yolox or nanodet\n"
                  "(default: detection.kind of the settings, else annotations when the sequence has annotations.jsonl,\n"
                  "else yolox)")
      ->check(CLI::IsMember({"annotations", "yolox", "nanodet"}));
  cmd->add_option("--classes", job.landmark_set, "Landmark class set of the network detectors: hospital, road or indoor "
                                                 "(default: detection.landmark_set of the settings, else road on KITTI, indoor otherwise)")
      ->check(CLI::IsMember({"hospital", "road", "indoor", "coco"}));
  cmd->add_option("--models", job.models_dir, "Folder searched first for the ONNX weights (then $WARDMAP_MODELS, ../shared/models)");
  cmd->add_flag("!--no-embedding", job.embedding, "Do not compute OSNet appearance embeddings");
  cmd->add_option_function<std::uint64_t>(
         "--seed", [&job](const std::uint64_t& seed) { job.seed = seed; },
         "Seed of the detector noise and of the Gibbs sampler (default: detection.annotations.seed, and 1)")
      ->check(whole_number());
}

void add_baseline_option(CLI::App* cmd, SemanticJob& job) {
  cmd->add_flag("!--no-baseline", job.baseline,
                "With the hierarchical association, do not also associate the measurements with the HDP-only\n"
                "baseline (reported beside it in the report and on the terminal; its map is not written)");
}

void add_run_command(CLI::App& app) {
  auto a = std::make_shared<RunArgs>();
  auto* cmd = app.add_subcommand(
      "run",
      "Run wardmap on a sequence and write a run folder: trajectory.txt, frames.csv, keyframes.txt, objects.json,\n"
      "measurements.jsonl, map.glb, report.json and report.md (with the object figures when the sequence has object ground truth).\n"
      "--poses slam runs the SLAM front-process, monocular or RGB-D (trajectory, frames, keyframes, points.ply,\n"
      "timing.csv, report with ATE and tracking rate), and with --objects the semantic layer on its keyframes;\n"
      "--poses gt runs the semantic layer on the sequence's ground-truth poses (needs depth).");
  cmd->add_option("sequence", a->job.sequence, "Sequence folder (TUM RGB-D, 7-Scenes, a wardmap synth output, ...)")->required();
  cmd->add_option("--out", a->job.out, "Run folder to write");
  cmd->add_option("--poses", a->poses, "Camera poses: slam (the front-process) or gt (the sequence's ground truth)")
      ->capture_default_str()
      ->check(CLI::IsMember({"gt", "slam"}));
  cmd->add_option("--mode", a->mode, "SLAM input: rgbd or mono (default: rgbd when the sequence has depth images, else mono)")->check(CLI::IsMember({"rgbd", "mono"}));
  cmd->add_option("--association", a->job.association,
                  "Object association: hierarchical (the paper) or hdp-only (HDP-SLAM baseline)\n"
                  "(default: semantics.association.mode of the settings, else hierarchical)")
      ->check(CLI::IsMember({"hierarchical", "hdp-only"}));
  cmd->add_option("--vocabulary", a->vocabulary, "Place-recognition vocabulary for relocalisation (default: "
                                                 "$WARDMAP_VOCABULARY, then data/vocabulary/orb-k10l4.bin)");
  cmd->add_flag("--objects", a->objects, "With --poses slam: also map the objects on the SLAM's keyframes (needs --out)");
  cmd->add_flag("--deterministic", a->deterministic, "Byte-identical output on reruns: local mapping runs on the tracking thread instead of its own");
  cmd->add_flag("--realtime", a->realtime,
                "Feed the frames at the sequence's own rate (their timestamps), as a live camera would. Without it\n"
                "frames are read as fast as they are tracked, and the tracker gives a busy mapper the\n"
                "sequence time since the last keyframe (mapping.sequence_time_for_mapper)")
      ->excludes("--deterministic");
  add_set_option(cmd, a->set, "Recorded in report.json (settings_overrides)");
  add_semantic_options(cmd, a->job);
  add_baseline_option(cmd, a->job);
  add_reader_options(cmd, a->reader);
  cmd->get_option("--settings")
      ->description("Settings YAML: camera (ORB-SLAM3 keys) and the tracking/mapping/semantics/detection sections.\n"
                    "A SLAM run (--poses slam) without it reads the sequence's settings.yaml, else the shipped\n"
                    "data/settings/ file for its dataset (KITTI by image width, 7-Scenes, EuRoC, TUM fr1/fr2/fr3)");
  cmd->callback([a] { run(*a); });
}

}  // namespace wardmap::apps
