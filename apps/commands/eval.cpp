// wardmap eval --gt <file|dataset> --est <file>: ATE, RPE and tracking rate (EVALUATION.md), scale drift.
#include <spdlog/spdlog.h>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <vector>

#include "apps/commands/commands.h"
#include "apps/common.h"
#include "slam/core/errors.h"
#include "slam/eval/trajectory_eval.h"
#include "slam/eval/trajectory_plot.h"
#include "slam/io/sequence.h"
#include "slam/io/text_file.h"
#include "slam/io/trajectory_io.h"

namespace wardmap::apps {

namespace fs = std::filesystem;
using slam::Trajectory;

namespace {

struct EvalArgs {
  std::string gt, est, align = "sim3", json, plot, errors, est_format = "auto";
  double max_dt = 0.02;
  int rpe_delta = 1;
  ReaderArgs reader;
};

// A run folder's frames.csv lists every frame the run read, tracked or not: the sequence's span.
// The ground truth is cut to it (half a frame period either side), as a dataset folder's is by its
// reader, so that poses recorded before or after the camera do not count as untracked time.
Trajectory cut_to_run_frames(const Trajectory& gt, const fs::path& frames_csv) {
  std::vector<double> t;
  slam::io::for_each_data_line(frames_csv, true, [&](long line, const std::vector<std::string>& tok) {
    if (line == 1 && tok.at(0) == "timestamp") return;  // the header
    t.push_back(slam::io::parse_double(tok.at(0), frames_csv, line, "timestamp"));
  });
  if (t.empty()) return gt;
  const double half_period = 0.5 * slam::eval::median_gap(t);
  Trajectory cut = gt.within(t.front() - half_period, t.back() + half_period);
  if (cut.size() < gt.size())
    spdlog::info("ground truth cut to the run's frames ({}): {} of its {} poses", frames_csv.string(), cut.size(),
                 gt.size());
  return cut;
}

nlohmann::json stats_json(const slam::eval::ErrorStats& s) {
  return {{"rmse", s.rmse}, {"mean", s.mean}, {"median", s.median}, {"max", s.max}, {"min", s.min}, {"std", s.std}};
}

void run_eval(const EvalArgs& a) {
  check_output_files({{a.json, "--json"}, {a.plot, "--plot"}, {a.errors, "--errors"}});
  const auto alignment = slam::eval::parse_alignment(a.align);
  // Ground truth: a pose file, or a dataset folder whose ground truth is read by its reader.
  Trajectory gt;
  std::unique_ptr<slam::io::SequenceReader> sequence;
  if (fs::is_directory(a.gt)) {
    sequence = slam::io::open_sequence(a.gt, reader_options(a.reader));
    gt = sequence->ground_truth();
    if (gt.empty()) throw InputError(a.gt, "the sequence has no ground truth");
  } else {
    if (a.reader.first_frame > 0 || a.reader.frames > 0)
      throw InputError(a.gt, "--first-frame and --frames cut a dataset's frames: give the dataset folder as --gt");
    gt = slam::io::read_trajectory(a.gt, slam::io::PoseFormat::Auto);
    if (const fs::path frames = fs::path(a.est) / "frames.csv"; !gt.indexed && fs::is_directory(a.est) && fs::exists(frames))
      gt = cut_to_run_frames(gt, frames);
  }
  const std::string est_file = file_or_run_file(a.est, "trajectory.txt").string();  // a pose file, or a run's
  Trajectory est = slam::io::read_trajectory(est_file, slam::io::parse_pose_format(a.est_format));
  if (est.indexed && sequence) {
    // A KITTI-format estimate has one pose per frame: give it the frames' timestamps.
    if (est.size() > sequence->size())
      throw InputError(est_file, "has " + std::to_string(est.size()) + " poses for a sequence of " +
                                     std::to_string(sequence->size()) + " frames");
    for (size_t i = 0; i < est.size(); ++i) est.timestamps[i] = sequence->timestamp(i);
    est.indexed = false;
  }
  if (gt.indexed != est.indexed)
    spdlog::warn("one file has no timestamps (KITTI format): poses are paired by their position in the files; "
                 "give the dataset folder to --gt to pair by time");

  if (!sequence && !fs::is_directory(a.est) && !gt.indexed && !est.indexed && !est.empty() &&
      (est.timestamps.front() - gt.timestamps.front() > 1.0 || gt.timestamps.back() - est.timestamps.back() > 1.0))
    spdlog::warn("the ground truth runs {:.1f} s before and {:.1f} s after the estimate, and all of it counts in the "
                 "tracking rate; if the camera's frames did not span it, give the dataset folder as --gt or the run "
                 "folder as --est",
                 std::max(0.0, est.timestamps.front() - gt.timestamps.front()),
                 std::max(0.0, gt.timestamps.back() - est.timestamps.back()));
  slam::eval::AssociationOptions assoc;
  assoc.max_dt = a.max_dt;
  const auto pairs = slam::eval::associate(gt, est, assoc);
  if (pairs.size() < 3 && alignment != slam::eval::Alignment::None)
    throw InputError(est_file, "only " + std::to_string(pairs.size()) + " poses pair with the ground truth (within " +
                                   std::to_string(a.max_dt) + " s); at least 3 are needed to align");
  if (pairs.empty()) throw InputError(est_file, "no pose pairs with the ground truth within the time window");
  const auto ate = slam::eval::compute_ate(gt, est, pairs, alignment);
  const auto rpe = slam::eval::compute_rpe(gt, est, pairs, a.rpe_delta, ate.scale);
  const double rate = slam::eval::tracking_rate(gt, est, assoc);
  const auto drift = slam::eval::compute_scale_drift(gt, est, pairs);

  std::printf("ground truth:   %s (%zu poses)\n", a.gt.c_str(), gt.size());
  std::printf("estimate:       %s (%zu poses)\n", est_file.c_str(), est.size());
  std::printf("pairs:          %zu (max dt %.3f s)\n", pairs.size(), a.max_dt);
  std::printf("alignment:      %s, scale %.9f\n", a.align.c_str(), ate.scale);
  std::printf("ATE RMSE:       %.9f m\n", ate.stats.rmse);
  std::printf("ATE mean/median/max: %.6f / %.6f / %.6f m\n", ate.stats.mean, ate.stats.median, ate.stats.max);
  std::printf("RPE (%d frame):  %.6f m, %.6f deg (RMSE)\n", rpe.delta, rpe.translation.rmse, rpe.rotation_deg.rmse);
  std::printf("scale drift:    %s\n", scale_drift_text(drift).c_str());
  std::printf("tracking rate:  %.2f %%\n", rate);

  if (!a.json.empty()) {
    const auto& T = ate.transform;
    nlohmann::json j = {{"ground_truth", a.gt},
                        {"estimate", est_file},
                        {"alignment", a.align},
                        {"max_dt", a.max_dt},
                        {"poses_ground_truth", gt.size()},
                        {"poses_estimate", est.size()},
                        {"pairs", pairs.size()},
                        {"scale", ate.scale},
                        {"ate", stats_json(ate.stats)},
                        {"rpe",
                         {{"delta_frames", rpe.delta},
                          {"count", rpe.count},
                          {"translation", stats_json(rpe.translation)},
                          {"rotation_deg", stats_json(rpe.rotation_deg)}}},
                        {"tracking_rate", rate},
                        {"scale_drift", scale_drift_json(drift)},
                        {"transform",
                         {{"scale", T.scale()},
                          {"rotation_xyzw", {T.rotation().x(), T.rotation().y(), T.rotation().z(), T.rotation().w()}},
                          {"translation", {T.translation().x(), T.translation().y(), T.translation().z()}}}}};
    slam::io::write_file_atomic(a.json, j.dump(2) + "\n");
  }
  if (!a.errors.empty()) {
    // One line per pose pair: where along the run the error builds up (the RMSE hides it).
    std::string csv = "timestamp,ate_m,dx_m,dy_m,dz_m,rotation_deg\n";
    for (size_t k = 0; k < pairs.size(); ++k) {
      const auto [i, j] = pairs[k];
      const slam::SE3 aligned = ate.transform.transform_pose(est.poses[j]);
      const Eigen::Vector3d d = aligned.translation() - gt.poses[i].translation();
      const double angle = gt.poses[i].rotation().angularDistance(aligned.rotation()) * 180.0 / M_PI;
      char line[160];
      std::snprintf(line, sizeof line, "%.6f,%.6f,%.6f,%.6f,%.6f,%.4f\n", est.timestamps[j], ate.errors[k], d.x(), d.y(),
                    d.z(), angle);
      csv += line;
    }
    slam::io::write_file_atomic(a.errors, csv);
  }
  if (!a.plot.empty()) {
    slam::eval::PlotSeries g{"ground truth", {}, cv::Scalar(40, 40, 40)};
    slam::eval::PlotSeries e{"estimate (" + a.align + " aligned)", {}, cv::Scalar(30, 60, 220)};
    for (const auto& p : gt.poses) g.points.push_back(p.translation());
    for (const auto& p : est.poses) e.points.push_back(ate.transform * p.translation());
    char title[200];
    std::snprintf(title, sizeof title, "ATE RMSE %.3f m (%s, scale %.3f), %zu pairs, tracked %.1f %%", ate.stats.rmse,
                  a.align.c_str(), ate.scale, pairs.size(), rate);
    slam::eval::save_png(a.plot, slam::eval::plot_top_view({g, e}, title));
  }
}

}  // namespace

void add_eval_command(CLI::App& app) {
  auto args = std::make_shared<EvalArgs>();
  auto* cmd = app.add_subcommand(
      "eval",
      "Evaluate an estimated trajectory against ground truth: ATE (RMSE, mean, median, max) after Umeyama alignment,\n"
      "RPE and tracking rate, as defined in docs/EVALUATION.md. Pose files: TUM (8 values a line) or KITTI (12).\n"
      "Also the scale drift: the estimate's displacement over each second against the truth's, divided by their\n"
      "mean; the slope of their least-squares line in % a second (negative: the estimate shrinks along the run).");
  cmd->add_option("--gt", args->gt,
                  "Ground truth: a TUM or KITTI pose file, or a dataset folder (its poses before the first frame or "
                  "after the last are left out of the tracking rate)")
      ->required();
  cmd->add_option("--est", args->est,
                  "Estimated trajectory: a TUM or KITTI pose file, or a run folder (its trajectory.txt; a pose file "
                  "as --gt is then cut to the frames of the run's frames.csv)")
      ->required();
  cmd->add_option("--align", args->align, "Alignment: sim3 (monocular), se3 (RGB-D, stereo) or none")->capture_default_str()
      ->check(CLI::IsMember({"sim3", "se3", "none"}));
  cmd->add_option("--max-dt", args->max_dt, "Largest time difference for a pose pair (s)")
      ->capture_default_str()
      ->check(positive_number());
  cmd->add_option("--rpe-delta", args->rpe_delta, "Frame gap of the relative pose error")
      ->capture_default_str()
      ->check(whole_number(1));
  cmd->add_option("--est-format", args->est_format, "Format of the estimate file")->capture_default_str()
      ->check(CLI::IsMember({"auto", "tum", "kitti"}));
  cmd->add_option("--json", args->json, "Write the figures as JSON to this file");
  cmd->add_option("--plot", args->plot, "Draw the aligned estimate over the ground truth (top view) to this PNG")
      ->check(png_file());
  cmd->add_option("--errors", args->errors,
                  "Write each pose pair's error after the alignment to this CSV: timestamp, ATE (m), its x/y/z "
                  "components (m, ground-truth frame) and the rotation error (deg)");
  add_reader_options(cmd, args->reader);
  cmd->callback([args] { run_eval(*args); });
}

}  // namespace wardmap::apps
