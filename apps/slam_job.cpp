#include "apps/slam_job.h"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <nlohmann/json.hpp>
#include <optional>
#include <string_view>
#include <thread>
#include <utility>

#include "apps/common.h"
#include "apps/detection_cache.h"
#include "apps/frame_prefetcher.h"
#include "apps/interrupt.h"
#include "apps/progress.h"
#include "slam/core/errors.h"
#include "slam/eval/challenge_recovery.h"
#include "slam/eval/trajectory_eval.h"
#include "slam/front/front_process.h"
#include "slam/io/sequence.h"
#include "slam/io/settings.h"
#include "slam/io/text_file.h"
#include "slam/io/trajectory_io.h"
#include "slam/place/vocabulary.h"

namespace wardmap::apps {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

// Keyframe images waiting for detection while the SLAM runs; a keyframe arriving when it is full is
// detected after the run instead (the tracker never waits). 16 VGA images: about 15 MB.
constexpr size_t kDetectionQueue = 16;

double percentile(std::vector<double> v, double q) {
  if (v.empty()) return 0;
  std::sort(v.begin(), v.end());
  return v[static_cast<size_t>(q * (v.size() - 1))];
}

// A file the project ships under data/: from the source tree the binary was built from, else from
// the working directory; empty when neither has it.
fs::path find_shipped(const fs::path& relative) {
  for (const fs::path& dir : {fs::path(WARDMAP_SOURCE_DIR) / "data", fs::path("data")})
    if (fs::exists(dir / relative)) return dir / relative;
  return {};
}

// With -v: where tracking was lost and found again, and why (the counts the tracker judged).
// submap_starts: the frame is the first since a new submap started.
void log_tracking_event(const slam::FrameResult& r, std::string_view status, std::string_view previous,
                        bool submap_starts, const slam::FrontOptions& options) {
  if (!spdlog::should_log(spdlog::level::debug)) return;
  const bool lost_now = status == "lost" && previous != "lost" && previous != "initialising" && !previous.empty();
  if (lost_now && r.inliers > 0)  // a pose came from the last frame or the reference keyframe, the local map failed
    spdlog::debug("frame {} ({:.3f} s): tracking lost in submap {}: {} local-map inliers, {} needed "
                  "(tracking.min_local_map_inliers)",
                  r.index, r.timestamp, r.submap, r.inliers, options.tracking.min_local_map_inliers);
  else if (lost_now)
    spdlog::debug("frame {} ({:.3f} s): tracking lost in submap {}: no pose from the last frame or the reference "
                  "keyframe ({} matches)",
                  r.index, r.timestamp, r.submap, r.matches);
  else if (status == "relocalised")
    spdlog::debug("frame {} ({:.3f} s): relocalised in submap {}, {} local-map inliers", r.index, r.timestamp,
                  r.submap, r.inliers);
  else if (status == "tracked" && (previous.empty() || previous == "initialising" || submap_starts))
    spdlog::debug("frame {} ({:.3f} s): submap {} initialised{}", r.index, r.timestamp, r.submap,
                  r.backfilled.empty() ? "" : fmt::format(", {} earlier frames backfilled", r.backfilled.size()));
  if (r.new_submap && !r.discarded_submap)
    spdlog::debug("frame {} ({:.3f} s): submap {} starts with the next frame", r.index, r.timestamp, r.submap + 1);
}

// A submap discarded (slam::FrameResult::discarded_submap): the frames localised in it, rows `first`
// on, become lost. Returns how many.
size_t unlocalise_discarded(std::vector<std::string>& statuses, size_t first) {
  size_t n = 0;
  for (size_t k = first; k < statuses.size(); ++k)
    if (statuses[k] != "lost" && statuses[k] != "initialising" && statuses[k] != "unreadable") statuses[k] = "lost", ++n;
  return n;
}

// A wrong depth factor (a TUM file's 5000 on a sensor that writes millimetres, ...) scales every
// depth: said at the first depth image, rather than left to show as a failed or drifting run.
void warn_if_depth_looks_off(const fs::path& sequence, const cv::Mat& depth, double factor, double max_depth) {
  std::vector<float> valid;
  for (int y = 0; y < depth.rows; y += 4)
    for (int x = 0; x < depth.cols; x += 4)
      if (const float d = depth.at<float>(y, x); d > 0) valid.push_back(d);
  if (valid.size() * 100 < static_cast<size_t>(depth.total() / 16)) {
    spdlog::warn("{}: under 1 % of the first depth image is valid", sequence.string());
    return;
  }
  auto mid = valid.begin() + static_cast<std::ptrdiff_t>(valid.size() / 2);
  std::nth_element(valid.begin(), mid, valid.end());
  const double within =
      static_cast<double>(std::count_if(valid.begin(), valid.end(), [&](float d) { return d <= max_depth; })) /
      valid.size();
  if (*mid < 0.3f || within < 0.2)
    spdlog::warn(
        "{}: the first depth image's median depth is {:.3g} m ({:.0f} % within tracking.max_depth {:g} m) with "
        "RGBD.DepthMapFactor {:g} (raw units per metre): check the factor (TUM 5000, millimetres 1000)",
        sequence.string(), *mid, 100 * within, max_depth, factor);
}

// How tracking fared through a synthetic sequence's challenge segments (challenges.txt), for
// report.json, report.md and the terminal: lost inside, localised again how long after each ends,
// and in which submap.
json challenges_json(const std::vector<slam::eval::ChallengeRecovery>& rec) {
  json out = json::array();
  for (const auto& r : rec)
    out.push_back({{"kind", r.segment.kind},
                   {"begin", r.segment.begin},
                   {"end", r.segment.end},
                   {"covered", r.covered},
                   {"frames_inside", r.frames_inside},
                   {"lost_inside", r.lost_inside},
                   {"submap_before", r.submap_before},
                   {"submap_after", r.submap_after},
                   {"new_submap", r.new_submap()},
                   {"localised_again_after_seconds", r.resumed_after ? json(*r.resumed_after) : json(nullptr)},
                   {"held_after_seconds", r.held_after ? json(*r.held_after) : json(nullptr)}});
  return out;
}

std::string challenges_markdown(const std::vector<slam::eval::ChallengeRecovery>& rec) {
  std::string md = fmt::format(
      "\n## Challenge segments (challenges.txt)\n\n"
      "Frames not localised inside each segment (lost or initialising), the first frame localised at or "
      "after its end (tracked, relocalised, or backfilled by a monocular initialisation), and the first from "
      "which tracking holds (it and the next {} frames localised, or all the frames left).\n\n"
      "| segment | kind | frames inside | not localised inside | localised again after its end | tracking held "
      "from | submap before -> after |\n"
      "|---|---|---|---|---|---|---|\n",
      slam::eval::kHoldFrames - 1);
  auto after = [](const std::optional<double>& t, bool covered) {
    return t ? fmt::format("{:.3f} s", *t) : covered ? std::string("never") : std::string("(the run ends first)");
  };
  for (const auto& r : rec) {
    const std::string again = after(r.resumed_after, r.covered);
    const std::string held = after(r.held_after, r.covered);
    const std::string submaps =
        r.resumed_after ? fmt::format("{} -> {}{}", r.submap_before, r.submap_after, r.new_submap() ? " (new)" : "")
                        : fmt::format("{} -> -", r.submap_before);
    md += fmt::format("| {:.3f}-{:.3f} s | {} | {} | {} | {} | {} | {} |\n", r.segment.begin, r.segment.end,
                      r.segment.kind, r.frames_inside, r.lost_inside, again, held, submaps);
  }
  return md;
}

std::string challenges_summary(const std::vector<slam::eval::ChallengeRecovery>& rec) {
  int lost = 0, renewed = 0, back = 0, held = 0;
  double slowest = 0, slowest_held = 0;
  for (const auto& r : rec) {
    lost += r.lost_inside > 0;
    renewed += r.new_submap();
    if (r.resumed_after) ++back, slowest = std::max(slowest, *r.resumed_after);
    if (r.held_after) ++held, slowest_held = std::max(slowest_held, *r.held_after);
  }
  return fmt::format(
      "challenge segments {}: lost inside {}, localised again after {} of them (at most {:.2f} s after the end), "
      "{} in a new submap; tracking held after {} of them (at most {:.2f} s after the end)\n",
      rec.size(), lost, back, slowest, renewed, held, slowest_held);
}

}  // namespace

fs::path find_vocabulary(const fs::path& given) {
  if (!given.empty()) {
    if (!fs::exists(given)) throw InputError(given.string(), "vocabulary file not found");
    return given;
  }
  // NOLINTNEXTLINE(concurrency-mt-unsafe): wardmap never calls setenv
  if (const char* env = std::getenv("WARDMAP_VOCABULARY"); env && *env) {
    if (!fs::exists(env)) throw InputError(env, "vocabulary file (WARDMAP_VOCABULARY) not found");
    return env;
  }
  return find_shipped("vocabulary/orb-k10l4.bin");
}

fs::path default_settings(const slam::io::SequenceInfo& info) {
  if (fs::exists(info.root / "settings.yaml")) return info.root / "settings.yaml";
  const std::string name = slam::io::suggest_settings_name(slam::io::to_string(info.kind), info.root, info.width);
  return name.empty() ? fs::path() : find_shipped(fs::path("settings") / name);
}

double run_slam_job(const SlamJob& job) {
  // A first Ctrl-C (or SIGTERM) while the run loads or tracks stops it after the frame in hand, and
  // the run folder is written for the frames so far; a second one quits at once. After tracking the
  // signals have their default action again (outputs are written whole or not at all).
  std::optional<InterruptScope> interrupt_scope(std::in_place);
  // Before looking for its calibration: a mistyped path should be reported as such.
  if (!fs::exists(job.sequence)) throw InputError(job.sequence.string(), "sequence not found (no such file or folder)");
  auto reader = slam::io::open_sequence(job.sequence, job.reader);
  const auto& info = reader->info();
  if (!info.notes.empty()) spdlog::info("{}: {}", job.sequence.string(), info.notes);
  if (!info.ground_truth_unmatched.empty())
    spdlog::warn("{}: {}; the run is not evaluated", job.sequence.string(), info.ground_truth_unmatched);
  fs::path settings_file = job.settings;
  if (settings_file.empty()) {
    settings_file = default_settings(info);
    if (settings_file.empty())
      throw InputError(job.sequence.string(),
                       "no calibration: give --settings (see data/settings/)" + enclosing_dataset_note(job.sequence));
    if (settings_file != info.root / "settings.yaml")
      spdlog::info("settings: {} (shipped for this dataset; --settings to give others)", settings_file.string());
  }
  slam::io::Settings settings;
  slam::FrontOptions options;
  slam::io::blame_overrides(job.settings_overrides, [&] {
    settings = slam::io::load_settings(settings_file, job.settings_overrides);
    options = slam::load_front_options(settings);
  });
  slam::io::fit_settings_to_sequence(settings, info, job.settings_overrides);
  warn_settings_notes(settings);
  if (settings.camera.depth_map_factor) reader->set_depth_factor(*settings.camera.depth_map_factor);
  const std::string mode = job.mode.empty() ? (info.has_depth ? "rgbd" : "mono") : job.mode;
  if (mode == "rgbd" && !info.has_depth)
    throw InputError(job.sequence.string(), "--mode rgbd needs depth images, and this sequence has none" +
                                                enclosing_dataset_note(job.sequence));
  options.monocular = mode == "mono";
  // A synthetic sequence's challenge segments: read before the run, so that a bad file is told now.
  std::vector<slam::eval::ChallengeSegment> challenges;
  if (fs::exists(info.root / "challenges.txt")) challenges = slam::eval::read_challenges(info.root / "challenges.txt");
  reader->set_decode_depth(!options.monocular);  // the monocular front-process never reads depth
  options.mapping_thread = !job.deterministic;
  if (job.realtime && job.deterministic)
    throw InputError("--realtime", "paces the input for the mapper thread, which --deterministic does not run");
  const auto& cam = settings.camera.camera;

  slam::FrontProcess front(options, cam);
  const fs::path vocabulary_file = find_vocabulary(job.vocabulary);
  if (vocabulary_file.empty())
    spdlog::warn("no place-recognition vocabulary found (give --vocabulary or set WARDMAP_VOCABULARY): "
                 "no relocalisation, a lost track starts a new submap");
  else
    front.set_vocabulary(std::make_shared<const slam::place::Vocabulary>(slam::place::Vocabulary::load(vocabulary_file)));
  std::string frames_csv = "timestamp,status,submap\n", timing_csv = "timestamp,seconds,extract_seconds,mapping_seconds,wait_seconds,flow,features,inliers,keyframe\n";
  std::vector<double> seconds, stamps;
  double wait_seconds = 0;  // the tracker waiting for a threaded mapper behind its time
  size_t flow_frames = 0;  // frames with the optical flow on (tracking.flow_extend / _mono, flow_budget_ms)
  std::vector<std::string> statuses;
  std::vector<int> submap_of;
  size_t submap_first_row = 0;    // the active submap's first frame
  size_t discarded_submaps = 0;   // submaps discarded (tracking.discard_submap_keyframes)
  UnreadableFrames unreadable;    // frames skipped (statuses "unreadable")
  char line[160];
  // Objects: keyframe images are detected (and embedded) on a thread of their own while the SLAM
  // runs; measurement and association wait for the final keyframe poses. --deterministic: after.
  SemanticJob objects_job;
  std::unique_ptr<SemanticSetup> objects_setup;
  if (job.objects) {
    objects_job = *job.objects;
    objects_job.sequence = job.sequence;
    objects_job.settings = settings_file;
    objects_job.out = job.out;
    objects_setup = prepare_semantic_job(objects_job);
    objects_job.setup = objects_setup.get();
    if (!job.deterministic) objects_setup->cache->start(kDetectionQueue);
  }
  Progress progress("slam", reader->size(), job.progress);
  std::optional<std::pair<std::chrono::steady_clock::time_point, double>> clock_start;  // --realtime
  // --deterministic tracks and maps on this thread: the next frames are decoded on the idle core. A
  // threaded run's tracker and mapper keep both cores busy, and it reads here.
  FramePrefetcher frames(*reader, job.deterministic ? 2 : 0);
  int interrupted = 0;
  for (size_t i = 0; i < reader->size(); ++i) {
    if ((interrupted = InterruptScope::requested())) break;
    progress.update(i + 1);
    slam::io::Frame frame;
    try {
      frame = frames.next();
    } catch (const FrameReadError& e) {  // as a dropped frame: the tracker never sees it
      unreadable.add(e, reader->timestamp(i));
      statuses.emplace_back("unreadable");
      submap_of.push_back(submap_of.empty() ? 0 : submap_of.back());
      stamps.push_back(reader->timestamp(i));
      continue;
    }
    if (statuses.size() == unreadable.size() && !frame.depth.empty())  // the first frame read
      warn_if_depth_looks_off(job.sequence, frame.depth, reader->info().depth_factor, options.tracking.max_depth);
    if (job.realtime) {  // the frame is delivered at its own time, measured from the first one's
      if (!clock_start) clock_start.emplace(std::chrono::steady_clock::now(), frame.timestamp);
      std::this_thread::sleep_until(clock_start->first +
                                    std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                                        std::chrono::duration<double>(frame.timestamp - clock_start->second)));
    }
    const slam::FrameResult r = front.process(frame);
    if (r.keyframe && objects_setup) objects_setup->cache->offer(frame.timestamp, frame.image);
    const char* status = r.relocalised ? "relocalised"
                         : r.tracked ? "tracked"
                         : r.state == slam::TrackingState::kNotInitialised ? "initialising"
                                                                           : "lost";
    log_tracking_event(r, status, statuses.empty() ? std::string_view() : std::string_view(statuses.back()),
                       statuses.size() == submap_first_row, options);
    statuses.push_back(status);
    submap_of.push_back(r.submap);
    stamps.push_back(r.timestamp);
    // Localised once the monocular map existed (a still start can make these thousands). Both lists
    // ascend: one pass back from the newest frame.
    size_t k = stamps.size();
    for (auto b = r.backfilled.rbegin(); b != r.backfilled.rend(); ++b) {
      while (k > 0 && stamps[k - 1] > *b) --k;
      if (k > 0 && stamps[k - 1] == *b) {
        statuses[k - 1] = "backfilled";
        submap_of[k - 1] = r.submap;
      }
    }
    if (r.discarded_submap) {
      ++discarded_submaps;
      const size_t n = unlocalise_discarded(statuses, submap_first_row);
      spdlog::debug("frame {} ({:.3f} s): submap {} discarded, left with at most {} keyframes "
                    "(tracking.discard_submap_keyframes): its {} localised frames are lost; a fresh submap {} "
                    "starts with the next frame",
                    r.index, r.timestamp, r.submap, options.tracking.discard_submap_keyframes, n, r.submap);
    }
    if (r.new_submap) submap_first_row = statuses.size();
    std::snprintf(line, sizeof line, "%.6f,%.6f,%.6f,%.6f,%.6f,%d,%d,%d,%d\n", r.timestamp, r.seconds,
                  r.extract_seconds, r.mapping_seconds, r.wait_seconds, r.flow ? 1 : 0, r.features, r.inliers,
                  r.keyframe ? 1 : 0);
    timing_csv += line;
    seconds.push_back(r.seconds);
    wait_seconds += r.wait_seconds;
    flow_frames += r.flow ? 1 : 0;
  }
  const size_t processed = stamps.size();
  progress.finish();
  if (interrupted)
    spdlog::warn("{}: stopped after frame {} of {}; writing the run folder for those frames{} (again to quit at once)",
                 signal_name(interrupted), processed, reader->size(), job.objects ? ", without objects" : "");
  unreadable.warn_summary(job.sequence);
  front.finish();
  interrupt_scope.reset();
  for (size_t k = 0; k < stamps.size(); ++k) {
    std::snprintf(line, sizeof line, "%.6f,%s,%d\n", stamps[k], statuses[k].c_str(), submap_of[k]);
    frames_csv += line;
  }

  const slam::Trajectory traj = front.trajectory();
  if (traj.empty() && processed > 0 && !interrupted)
    spdlog::warn("{}: no frame was tracked: {}", job.sequence.string(),
                 mode == "mono"
                     ? "no two frames had the matches and parallax to initialise (tracking.init_*)"
                     : "initialising needs " + std::to_string(options.tracking.min_init_points) +
                           " keypoints with a depth up to " + fmt::format("{:g}", options.tracking.max_depth) +
                           " m (tracking.min_init_points, tracking.max_depth): check the depth images and "
                           "RGBD.DepthMapFactor, or run --mode mono");
  json report = {{"sequence", job.sequence.string()}, {"mode", mode}, {"settings", settings_file.string()},
                 {"realtime", job.realtime},
                 {"frames", reader->size()}, {"frames_processed", processed}, {"frames_in_final_map", traj.size()}, {"submaps", front.submaps().size()},
                 {"submaps_discarded", discarded_submaps},
                 {"tracking_ms", {{"median", 1e3 * percentile(seconds, 0.5)}, {"p95", 1e3 * percentile(seconds, 0.95)},
                                  {"max", 1e3 * percentile(seconds, 1.0)}}},
                 // keyframes the threaded mapper registered without fusion, BA and culling (it was behind)
                 {"mapper_deferred_keyframes", front.mapper_stats().deferred},
                 // local BAs the threaded mapper cut short: a keyframe was waiting or wanted by the tracker
                 {"mapper_aborted_bas", front.mapper_stats().ba_aborted},
                 // the tracker waiting for a threaded mapper still busy (the sequence time since the last
                 // keyframe, or mapping.max_lag_frames after it)
                 {"mapper_wait_seconds", wait_seconds},
                 // frames with the optical flow on: all with it on and no budget, fewer when it was over
                 // tracking.flow_budget_ms(_mono), none with it off
                 {"flow_frames", flow_frames}};
  report["first_frame"] = reader->first_frame();  // of the stretch run (--first-frame)
  report["settings_overrides"] = overrides_json(job.settings_overrides);  // --set KEY=VALUE, in order
  report["settings_notes"] = settings.notes;                              // keys that look meant but are not read
  report["unreadable_frames"] = unreadable.to_json();                     // skipped, "unreadable" in frames.csv
  if (interrupted) report["interrupted"] = signal_name(interrupted);
  {
    // What local mapping did, over the run (all submaps).
    const auto& m = front.mapper_stats();
    report["mapping"] = {{"keyframes", m.keyframes},         {"points_triangulated", m.triangulated},
                         {"points_culled", m.culled_points}, {"points_fused", m.fused},
                         {"keyframes_culled", m.culled_keyframes}};
    // Wall time per mapped keyframe of each local-mapping stage (ms).
    const double per_kf = m.keyframes > 0 ? 1e3 / m.keyframes : 0.0;
    report["mapping_ms_per_keyframe"] = {
        {"register", per_kf * m.t_register}, {"cull_points", per_kf * m.t_cull},
        {"triangulate", per_kf * m.t_triangulate}, {"fuse", per_kf * m.t_fuse},
        {"local_ba", per_kf * m.t_ba}, {"cull_keyframes", per_kf * m.t_cull_keyframes}};
  }
  double rate = -1;
  std::string md = "# wardmap run (SLAM front-process)\n\n- sequence: `" + job.sequence.string() + "`\n- mode: " + mode +
                   (job.deterministic ? ", deterministic (mapping inline)" : job.realtime ? ", threaded, input at the sequence's rate (--realtime)" : ", threaded") +
                   "\n- frames: " + std::to_string(reader->size()) + ", in the final map: " + std::to_string(traj.size()) +
                   ", submaps: " + std::to_string(front.submaps().size()) +
                   (discarded_submaps ? " (and " + std::to_string(discarded_submaps) + " discarded, too small to keep)" : "") + "\n";
  md += "- settings: `" + settings_file.string() + "`" + overrides_text(job.settings_overrides) + "\n" +
        settings_notes_text(settings.notes);
  if (!unreadable.empty()) md += "- " + unreadable.summary() + ": not tracked\n";
  if (interrupted)
    md += "- interrupted (" + signal_name(interrupted) + ") after frame " + std::to_string(processed) + " of " +
          std::to_string(reader->size()) + ": the figures below are for those frames\n";
  char buf[256];
  std::snprintf(buf, sizeof buf, "- tracking time per frame: median %.1f ms, p95 %.1f ms\n", 1e3 * percentile(seconds, 0.5),
                1e3 * percentile(seconds, 0.95));
  md += buf;
  md += "- keyframes mapped without fusion, BA and culling (threaded mapper behind): " +
        std::to_string(front.mapper_stats().deferred) + "\n- local BAs cut short (a keyframe waiting or wanted): " +
        std::to_string(front.mapper_stats().ba_aborted) + "\n";
  std::snprintf(buf, sizeof buf, "- tracker waiting for the mapper (threaded, behind its time): %.1f s\n", wait_seconds);
  md += buf;
  std::snprintf(buf, sizeof buf, "- optical flow: on %zu of %zu frames\n", flow_frames, processed);
  md += buf;
  {
    const json& t = report["mapping_ms_per_keyframe"];
    const auto ms = [&](const char* stage) { return t.at(stage).get<double>(); };
    std::snprintf(buf, sizeof buf,
                  "- local mapping per keyframe (%d): register %.1f ms, point culling %.1f ms, triangulation %.1f ms, "
                  "fusion %.1f ms, local BA %.1f ms, keyframe culling %.1f ms\n",
                  front.mapper_stats().keyframes, ms("register"), ms("cull_points"), ms("triangulate"), ms("fuse"),
                  ms("local_ba"), ms("cull_keyframes"));
    md += buf;
  }
  if (info.has_ground_truth && !stamps.empty()) {
    // An interrupted run is evaluated on the ground truth up to its last frame.
    slam::Trajectory gt;
    for (size_t k = 0; k < reader->ground_truth().size(); ++k)
      if (!interrupted || reader->ground_truth().timestamps[k] <= stamps.back() + 1e-9)
        gt.push_back(reader->ground_truth().timestamps[k], reader->ground_truth().poses[k]);
    const auto pairs = slam::eval::associate(gt, traj, {});
    rate = slam::eval::tracking_rate(gt, traj, {});
    if (pairs.size() >= 3) {
      // Monocular maps have no metric scale: Sim(3) alignment (EVALUATION.md); RGB-D: SE(3).
      const bool mono = mode == "mono";
      const char* name = mono ? "Sim(3)" : "SE(3)";
      const auto ate =
          slam::eval::compute_ate(gt, traj, pairs, mono ? slam::eval::Alignment::Sim3 : slam::eval::Alignment::SE3);
      report[mono ? "ate_sim3" : "ate_se3"] = {{"rmse", ate.stats.rmse}, {"mean", ate.stats.mean},
                                              {"median", ate.stats.median}, {"max", ate.stats.max},
                                              {"pairs", pairs.size()}};
      std::snprintf(buf, sizeof buf, "- ATE (%s) RMSE %.4f m, median %.4f m, max %.4f m over %zu poses\n", name,
                    ate.stats.rmse, ate.stats.median, ate.stats.max, pairs.size());
      md += buf;
      std::printf("ATE (%s) RMSE %.4f m over %zu poses\n", name, ate.stats.rmse, pairs.size());
      // How the scale changes along the run: the monocular drift's diagnostic (RGB-D too).
      const auto drift = slam::eval::compute_scale_drift(gt, traj, pairs);
      report["scale_drift"] = scale_drift_json(drift);
      if (drift.valid) md += "- scale drift " + scale_drift_text(drift) + "\n";
    }
    report["tracking_rate"] = rate;
    std::snprintf(buf, sizeof buf, "- tracking rate %.1f %%\n", rate);
    md += buf;
    std::printf("tracking rate %.1f %%\n", rate);
  }
  if (!challenges.empty()) {
    std::vector<slam::eval::FrameState> states;
    states.reserve(stamps.size());
    for (size_t k = 0; k < stamps.size(); ++k) states.push_back({stamps[k], statuses[k], submap_of[k]});
    const auto recovery = slam::eval::challenge_recovery(states, challenges);
    report["challenges"] = challenges_json(recovery);
    if (!recovery.empty()) {
      md += challenges_markdown(recovery);
      std::printf("%s", challenges_summary(recovery).c_str());
    }
  }
  std::printf("frames %zu%s, in the final map %zu, submaps %zu, median tracking time %.1f ms\n", processed,
              interrupted ? (" of " + std::to_string(reader->size()) + " (interrupted)").c_str() : "", traj.size(),
              front.submaps().size(), 1e3 * percentile(seconds, 0.5));

  if (!job.out.empty()) {
    namespace io = slam::io;
    io::write_tum(job.out / "trajectory.txt", traj);
    io::write_file_atomic(job.out / "frames.csv", frames_csv);
    io::write_file_atomic(job.out / "timing.csv", timing_csv);
    // Keyframes and points of the submap that holds the final trajectory (the largest).
    const slam::Submap* best = nullptr;
    size_t best_n = 0;
    for (const auto& s : front.submaps())
      if (!best || front.trajectory(s->id()).size() > best_n) best = s.get(), best_n = front.trajectory(s->id()).size();
    slam::Trajectory kfs;
    std::vector<std::vector<Eigen::Vector3d>> keyframe_points;
    std::string ply_body;
    std::vector<Eigen::Vector3d> world_points;  // the same points, for the object map's map.glb
    size_t points = 0;
    if (best) {
      std::vector<std::shared_ptr<slam::KeyFrame>> list;
      for (const auto& [id, kf] : best->keyframes())
        if (!kf->bad()) list.push_back(kf);
      std::sort(list.begin(), list.end(), [](const auto& a, const auto& b) { return a->timestamp() < b->timestamp(); });
      for (const auto& kf : list) {
        const slam::SE3 T_cw = slam::resolved_pose_cw(kf);
        kfs.push_back(kf->timestamp(), T_cw.inverse());
        if (!options.monocular || !job.objects) continue;
        // Monocular objects are measured on each keyframe's map points, in its camera frame.
        auto& pts = keyframe_points.emplace_back();
        for (const auto& mp : kf->map_points())
          if (mp && !mp->bad()) pts.push_back(T_cw * mp->position());
      }
      for (const auto& [id, p] : best->map_points()) {
        if (p->bad()) continue;
        std::snprintf(line, sizeof line, "%.5f %.5f %.5f\n", p->position().x(), p->position().y(), p->position().z());
        ply_body += line;
        if (job.objects) world_points.push_back(p->position());
        ++points;
      }
    }
    io::write_tum(job.out / "keyframes.txt", kfs);
    io::write_file_atomic(job.out / "points.ply", "ply\nformat ascii 1.0\nelement vertex " + std::to_string(points) +
                                                      "\nproperty float x\nproperty float y\nproperty float z\nend_header\n" +
                                                      ply_body);
    report["keyframes"] = kfs.size();
    if (job.objects && !interrupted) {
      SemanticJob& sj = objects_job;
      sj.keyframes = &kfs;
      sj.trajectory = &traj;
      if (options.monocular) sj.keyframe_points = &keyframe_points;
      sj.map_points = &world_points;
      const SemanticRun objects = run_semantic_job(sj);
      report["landmarks"] = objects.result.landmarks.size();
      std::printf("objects: %zu landmarks on %zu keyframes\n", objects.result.landmarks.size(), objects.keyframes.size());
      std::printf("objects by class: %s\n", format_landmark_counts(objects.result).c_str());
      if (objects.evaluation) std::printf("%s", format_object_evaluation(*objects.evaluation).c_str());
      if (objects.baseline) std::printf("against the HDP-only baseline:\n%s", format_baseline_comparison(objects).c_str());
    }
    report["map_points"] = points;
    io::write_file_atomic(job.out / "report.json", report.dump(2) + "\n");
    io::write_file_atomic(job.out / "report.md", md);
    std::printf("outputs in %s\n", job.out.c_str());
  }
  if (interrupted)
    throw Interrupted(interrupted, "interrupted (" + signal_name(interrupted) + ") after frame " + std::to_string(processed) +
                                       " of " + std::to_string(reader->size()) + "; " +
                                       (job.out.empty() ? std::string("nothing written (no --out)")
                                                        : "the run folder " + job.out.string() + " holds those frames"));
  return rate;
}

}  // namespace wardmap::apps
