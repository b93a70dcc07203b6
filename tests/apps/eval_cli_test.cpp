// wardmap eval against figures computed independently here: ground truth against itself moved by a
// known Sim(3) plus noise. The test aligns with Horn's quaternion method (not the SVD of Umeyama
// that wardmap uses) and compares ATE and scale to 1e-6.
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <random>
#include <sstream>

#include "slam/core/sim3.h"
#include "slam/io/trajectory_io.h"
#include "tests/apps/cli_support.h"
#include "tests/slam/io/fixtures.h"

namespace wardmap::test {
namespace {

namespace fs = std::filesystem;
using slam::SE3;
using slam::Sim3;
using slam::Trajectory;

struct Reference {
  double rmse, scale;
};

// Horn (1987) closed-form absolute orientation with the asymmetric scale of least squares.
Reference horn_ate(const std::vector<Eigen::Vector3d>& est, const std::vector<Eigen::Vector3d>& gt, bool with_scale) {
  const size_t n = est.size();
  Eigen::Vector3d ma = Eigen::Vector3d::Zero(), mb = Eigen::Vector3d::Zero();
  for (size_t i = 0; i < n; ++i) ma += est[i], mb += gt[i];
  ma /= n, mb /= n;
  Eigen::Matrix3d M = Eigen::Matrix3d::Zero();
  double saa = 0;
  for (size_t i = 0; i < n; ++i) {
    M += (est[i] - ma) * (gt[i] - mb).transpose();
    saa += (est[i] - ma).squaredNorm();
  }
  const double Sxx = M(0, 0), Sxy = M(0, 1), Sxz = M(0, 2), Syx = M(1, 0), Syy = M(1, 1), Syz = M(1, 2), Szx = M(2, 0),
               Szy = M(2, 1), Szz = M(2, 2);
  Eigen::Matrix4d N;
  N << Sxx + Syy + Szz, Syz - Szy, Szx - Sxz, Sxy - Syx,  //
      Syz - Szy, Sxx - Syy - Szz, Sxy + Syx, Szx + Sxz,   //
      Szx - Sxz, Sxy + Syx, -Sxx + Syy - Szz, Syz + Szy,  //
      Sxy - Syx, Szx + Sxz, Syz + Szy, -Sxx - Syy + Szz;
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix4d> eig(N);
  const Eigen::Vector4d q = eig.eigenvectors().col(3);  // largest eigenvalue
  const Eigen::Matrix3d R = Eigen::Quaterniond(q(0), q(1), q(2), q(3)).normalized().toRotationMatrix();
  double num = 0;
  for (size_t i = 0; i < n; ++i) num += (gt[i] - mb).dot(R * (est[i] - ma));
  const double s = with_scale ? num / saa : 1.0;
  const Eigen::Vector3d t = mb - s * R * ma;
  double sq = 0;
  for (size_t i = 0; i < n; ++i) sq += (s * R * est[i] + t - gt[i]).squaredNorm();
  return {std::sqrt(sq / n), s};
}

// A wandering 3-D path (a corridor walk with turns and height changes), 200 poses at 30 Hz.
Trajectory ground_truth() {
  Trajectory t;
  for (int i = 0; i < 200; ++i) {
    const double a = i * 0.03;
    t.push_back(10.0 + i / 30.0, SE3(Eigen::Quaterniond(Eigen::AngleAxisd(0.5 * std::sin(a), Eigen::Vector3d::UnitY())),
                                     Eigen::Vector3d(4 * std::sin(a), 0.3 * std::cos(2 * a), 2 * a)));
  }
  return t;
}

struct Case {
  std::vector<Eigen::Vector3d> est_points, gt_points;
};

Case make_estimate(const Trajectory& gt, const Sim3& S, double noise, Trajectory& est) {
  std::mt19937 rng(42);
  std::normal_distribution<double> n(0.0, noise);
  Case c;
  est = gt;
  for (size_t i = 0; i < gt.size(); ++i) {
    const SE3 moved = S.transform_pose(gt.poses[i]);
    est.poses[i] = SE3(moved.rotation(), moved.translation() + Eigen::Vector3d(n(rng), n(rng), n(rng)));
    c.est_points.push_back(est.poses[i].translation());
    c.gt_points.push_back(gt.poses[i].translation());
  }
  return c;
}

// Writes its --json and --plot into `out_dir`, by default the estimate's folder (never the shared
// data's: a test must not write there).
nlohmann::json run_eval(const fs::path& gt, const fs::path& est, const std::string& align, fs::path out_dir = {}) {
  const fs::path out = (out_dir.empty() ? est.parent_path() : out_dir) / ("eval-" + align + ".json");
  const CliResult r = wardmap_cli("eval --gt " + shq(gt) + " --est " + shq(est) + " --align " + align + " --json " +
                                  shq(out) + " --plot " + shq(out.string() + ".png"));
  EXPECT_EQ(r.code, 0) << r.output;
  EXPECT_TRUE(fs::exists(out.string() + ".png"));
  std::ifstream in(out);
  return nlohmann::json::parse(in);
}

const Sim3 kTruth(0.42, Eigen::Quaterniond(Eigen::AngleAxisd(2.2, Eigen::Vector3d(0.3, -1, 0.5).normalized())),
                  Eigen::Vector3d(5, -3, 12));

TEST(EvalCli, TumSim3MatchesIndependentComputation) {
  const fs::path dir = scratch_dir();
  const Trajectory gt = ground_truth();
  Trajectory est;
  const Case c = make_estimate(gt, kTruth, 0.01, est);
  slam::io::write_tum(dir / "gt.txt", gt);
  slam::io::write_tum(dir / "est.txt", est);
  // The file stores 9 decimals: the reference reads the same rounded values back.
  const Trajectory est_read = slam::io::read_trajectory(dir / "est.txt");
  std::vector<Eigen::Vector3d> pts;
  for (const auto& p : est_read.poses) pts.push_back(p.translation());
  const Reference ref = horn_ate(pts, c.gt_points, true);
  const nlohmann::json j = run_eval(dir / "gt.txt", dir / "est.txt", "sim3");
  EXPECT_EQ(j["pairs"].get<int>(), 200);
  EXPECT_NEAR(j["ate"]["rmse"].get<double>(), ref.rmse, 1e-6);
  EXPECT_NEAR(j["scale"].get<double>(), ref.scale, 1e-6);
  EXPECT_NEAR(ref.scale, 1 / 0.42, 0.01);  // sanity: the noise is small
  EXPECT_GT(ref.rmse, 0.005);
  EXPECT_NEAR(j["tracking_rate"].get<double>(), 100.0, 1e-9);
  // A similarity of the truth with 1 cm noise: six 1-s windows, no scale drift beyond the noise.
  EXPECT_EQ(j["scale_drift"]["windows"].get<int>(), 6) << j["scale_drift"].dump();
  EXPECT_LT(std::abs(j["scale_drift"]["slope_percent_per_s"].get<double>()), 1.5) << j["scale_drift"].dump();
}

TEST(EvalCli, KittiFormatSim3AndSe3) {
  const fs::path dir = scratch_dir();
  const Trajectory gt = ground_truth();
  for (const bool with_scale : {true, false}) {
    Trajectory est;
    const Case c = make_estimate(gt, with_scale ? kTruth : Sim3(1.0, kTruth.rotation(), kTruth.translation()), 0.02, est);
    slam::io::write_kitti(dir / "gt.txt", gt);
    slam::io::write_kitti(dir / "est.txt", est);
    std::vector<Eigen::Vector3d> pe, pg;
    for (const auto& p : slam::io::read_trajectory(dir / "est.txt").poses) pe.push_back(p.translation());
    for (const auto& p : slam::io::read_trajectory(dir / "gt.txt").poses) pg.push_back(p.translation());
    const Reference ref = horn_ate(pe, pg, with_scale);
    const nlohmann::json j = run_eval(dir / "gt.txt", dir / "est.txt", with_scale ? "sim3" : "se3");
    EXPECT_EQ(j["pairs"].get<int>(), 200);
    EXPECT_NEAR(j["ate"]["rmse"].get<double>(), ref.rmse, 1e-6) << (with_scale ? "sim3" : "se3");
    EXPECT_NEAR(j["scale"].get<double>(), ref.scale, 1e-6);
    EXPECT_TRUE(j["scale_drift"]["slope_percent_per_s"].is_null()) << "KITTI pose files have no time";
  }
}

TEST(EvalCli, TumSe3) {
  const fs::path dir = scratch_dir();
  const Trajectory gt = ground_truth();
  Trajectory est;
  make_estimate(gt, Sim3(1.0, kTruth.rotation(), kTruth.translation()), 0.03, est);
  slam::io::write_tum(dir / "gt.txt", gt);
  slam::io::write_tum(dir / "est.txt", est);
  std::vector<Eigen::Vector3d> pe, pg;
  for (const auto& p : slam::io::read_trajectory(dir / "est.txt").poses) pe.push_back(p.translation());
  for (const auto& p : slam::io::read_trajectory(dir / "gt.txt").poses) pg.push_back(p.translation());
  const Reference ref = horn_ate(pe, pg, false);
  const nlohmann::json j = run_eval(dir / "gt.txt", dir / "est.txt", "se3");
  EXPECT_NEAR(j["ate"]["rmse"].get<double>(), ref.rmse, 1e-6);
  EXPECT_DOUBLE_EQ(j["scale"].get<double>(), 1.0);

  // --est takes a run folder (its trajectory.txt) too.
  slam::io::write_tum(dir / "run" / "trajectory.txt", est);
  const nlohmann::json from_folder = run_eval(dir / "gt.txt", dir / "run", "se3");
  EXPECT_EQ(from_folder["estimate"].get<std::string>(), (dir / "run" / "trajectory.txt").string());
  EXPECT_EQ(from_folder["ate"], j["ate"]);
  const CliResult not_a_run = wardmap_cli("eval --gt " + shq(dir / "gt.txt") + " --est " + shq(dir));
  EXPECT_NE(not_a_run.output.find("trajectory.txt: not found: is this a wardmap run folder?"), std::string::npos)
      << not_a_run.output;
  // An output that names a folder is refused before the evaluation; before, the figures were
  // printed and the --json then failed with "cannot rename the temporary file into place: Success".
  const CliResult to_folder =
      wardmap_cli("eval --gt " + shq(dir / "gt.txt") + " --est " + shq(dir / "run") + " --json " + shq(dir / "run"));
  EXPECT_EQ(to_folder.code, 2) << to_folder.output;
  EXPECT_NE(to_folder.output.find("--json names a folder; it must be a file"), std::string::npos) << to_folder.output;
  EXPECT_EQ(to_folder.output.find("ATE"), std::string::npos) << "evaluated first:\n" << to_folder.output;
}

// --errors: one CSV line per pose pair after the alignment. The estimate is the ground truth moved
// by a known Sim(3), with pose 50 displaced by a known vector and turned by a known angle: after
// the Sim(3) alignment (fitted on 200 poses, one of them off) that pose's line shows them.
TEST(EvalCli, PerPoseErrorsAfterTheAlignment) {
  const fs::path dir = scratch_dir();
  const Trajectory gt = ground_truth();
  Trajectory est;
  make_estimate(gt, kTruth, 0.0, est);
  // Displace pose 50 in the ground truth's frame: 0.2 m along x and 3 degrees about z.
  const SE3 off(Eigen::Quaterniond(Eigen::AngleAxisd(3.0 * M_PI / 180.0, Eigen::Vector3d::UnitZ())) *
                    gt.poses[50].rotation(),
                gt.poses[50].translation() + Eigen::Vector3d(0.2, 0, 0));
  est.poses[50] = kTruth.transform_pose(off);
  slam::io::write_tum(dir / "gt.txt", gt);
  slam::io::write_tum(dir / "est.txt", est);
  const CliResult r = wardmap_cli("eval --gt " + shq(dir / "gt.txt") + " --est " + shq(dir / "est.txt") +
                                  " --align sim3 --errors " + shq(dir / "errors.csv"));
  ASSERT_EQ(r.code, 0) << r.output;
  std::ifstream in(dir / "errors.csv");
  std::string line;
  std::getline(in, line);
  EXPECT_EQ(line, "timestamp,ate_m,dx_m,dy_m,dz_m,rotation_deg");
  std::vector<std::vector<double>> rows;
  while (std::getline(in, line)) {
    std::vector<double> v;
    std::stringstream ss(line);
    for (std::string cell; std::getline(ss, cell, ',');) v.push_back(std::stod(cell));
    ASSERT_EQ(v.size(), 6u) << line;
    rows.push_back(v);
  }
  ASSERT_EQ(rows.size(), gt.size());
  // The one displaced pose pulls the fit by about 1/200 of its offset: 1 mm, 0.015 degrees.
  EXPECT_NEAR(rows[50][0], gt.timestamps[50], 1e-6);
  EXPECT_NEAR(rows[50][2], 0.2, 0.003);
  EXPECT_NEAR(rows[50][3], 0.0, 0.003);
  EXPECT_NEAR(rows[50][4], 0.0, 0.003);
  EXPECT_NEAR(rows[50][1], std::hypot(rows[50][2], rows[50][3], rows[50][4]), 1e-5);
  EXPECT_NEAR(rows[50][5], 3.0, 0.05);
  for (size_t k = 0; k < rows.size(); ++k)
    if (k != 50) {
      EXPECT_LT(rows[k][1], 0.003) << k;
      EXPECT_LT(rows[k][5], 0.05) << k;
    }
}

// A TUM RGB-D folder of 10 frames at 30 Hz from t0 (rgb/, depth/, rgb.txt, depth.txt, no ground
// truth); returns the frames' timestamps as the index files write them.
std::vector<std::string> write_tum_frames(const fs::path& tum, double t0) {
  std::string rgb, depth;
  std::vector<std::string> times;
  for (int i = 0; i < 10; ++i) {
    const std::string n = std::to_string(i), t = std::to_string(t0 + i / 30.0);
    write_image(tum / "rgb" / (n + ".png"), i);
    write_depth(tum / "depth" / (n + ".png"), 5000);
    rgb += t + " rgb/" + n + ".png\n";
    depth += t + " depth/" + n + ".png\n";
    times.push_back(t);
  }
  write_text(tum / "rgb.txt", rgb);
  write_text(tum / "depth.txt", depth);
  return times;
}

// --first-frame / --frames with a dataset as --gt: the ground truth of the stretch alone, so an
// estimate of that stretch is fully tracked; with a pose file as --gt they are refused.
TEST(EvalCli, AStretchOfADatasetIsScoredOnItsOwnFrames) {
  const fs::path dir = scratch_dir();
  // TUM RGB-D: 10 frames at 30 Hz with ground truth at x = i; the estimate has frames 5-9, exact.
  const std::vector<std::string> times = write_tum_frames(dir / "tum", 1.0);
  std::string gt, est;
  for (int i = 0; i < 10; ++i) {
    const std::string n = std::to_string(i), &t = times[static_cast<size_t>(i)];
    gt += t + " " + n + " 0 0 0 0 0 1\n";
    if (i >= 5) est += t + " " + n + " 0 0 0 0 0 1\n";
  }
  write_text(dir / "tum" / "groundtruth.txt", gt);
  write_text(dir / "est.txt", est);
  const auto eval = [&](const std::string& extra) {
    const fs::path out = dir / "eval.json";
    fs::remove(out);
    const CliResult r = wardmap_cli("eval --gt " + shq(dir / "tum") + " --est " + shq(dir / "est.txt") +
                                    " --align none --json " + shq(out) + extra);
    EXPECT_EQ(r.code, 0) << r.output;
    std::ifstream in(out);
    return nlohmann::json::parse(in);
  };
  const nlohmann::json whole = eval(""), stretch = eval(" --first-frame 5 --frames 5");
  EXPECT_EQ(whole["pairs"].get<int>(), 5);
  EXPECT_NEAR(whole["tracking_rate"].get<double>(), 50.0, 0.01);  // frames 0-4 not in the estimate (6-decimal times)
  EXPECT_EQ(stretch["pairs"].get<int>(), 5);
  EXPECT_NEAR(stretch["tracking_rate"].get<double>(), 100.0, 0.01);
  EXPECT_LT(stretch["ate"]["rmse"].get<double>(), 1e-9);

  write_text(dir / "gt.txt", gt);
  const CliResult refused =
      wardmap_cli("eval --gt " + shq(dir / "gt.txt") + " --est " + shq(dir / "est.txt") + " --align none --frames 1");
  EXPECT_EQ(refused.code, 2) << refused.output;
  EXPECT_NE(refused.output.find("give the dataset folder as --gt"), std::string::npos) << refused.output;
}

TEST(EvalCli, GroundTruthRecordedBeyondTheFramesIsNotUntrackedTime) {
  const fs::path dir = scratch_dir();
  // TUM RGB-D as recorded: the motion capture (100 Hz) runs from 1 s before the first of 10 frames
  // (30 Hz) to 1 s after the last; the estimate has every frame, exact.
  const std::vector<std::string> times = write_tum_frames(dir / "tum", 2.0);
  std::string gt, est, est_late;
  for (int i = 0; i < 10; ++i) {
    const std::string line = times[static_cast<size_t>(i)] + " " + std::to_string(0.1 * (2.0 + i / 30.0)) + " 0 0 0 0 0 1\n";
    est += line;
    if (i >= 5) est_late += line;
  }
  for (int k = 100; k <= 330; ++k) gt += std::to_string(k / 100.0) + " " + std::to_string(0.1 * k / 100.0) + " 0 0 0 0 0 1\n";
  write_text(dir / "tum" / "groundtruth.txt", gt);
  write_text(dir / "est.txt", est);
  const fs::path out = dir / "eval.json";
  const CliResult r = wardmap_cli("eval --gt " + shq(dir / "tum") + " --est " + shq(dir / "est.txt") +
                                  " --align none --json " + shq(out));
  ASSERT_EQ(r.code, 0) << r.output;
  std::ifstream in(out);
  const nlohmann::json j = nlohmann::json::parse(in);
  EXPECT_NEAR(j["tracking_rate"].get<double>(), 100.0, 0.01);  // 15 % when the whole 2.3 s capture counted
  EXPECT_EQ(j["pairs"].get<int>(), 10);
  EXPECT_LT(j["ate"]["rmse"].get<double>(), 1e-3);  // paired with the capture pose within 5 ms, at 0.1 m/s

  // The motion capture as a bare file: cut to a run folder's frames (frames.csv), not to a bare
  // estimate's, which has no frames to cut to.
  write_text(dir / "gt.txt", gt);
  const auto rate_against = [&](const fs::path& est_arg) {
    const CliResult e = wardmap_cli("eval --gt " + shq(dir / "gt.txt") + " --est " + shq(est_arg) +
                                    " --align none --json " + shq(out));
    EXPECT_EQ(e.code, 0) << e.output;
    std::ifstream j(out);
    return nlohmann::json::parse(j)["tracking_rate"].get<double>();
  };
  EXPECT_LT(rate_against(dir / "est.txt"), 50.0);
  std::string frames = "timestamp,status,submap\n";
  for (int i = 0; i < 10; ++i) frames += std::to_string(2.0 + i / 30.0) + (i < 5 ? ",lost,-1\n" : ",tracked,0\n");
  write_text(dir / "run" / "frames.csv", frames);
  write_text(dir / "run" / "trajectory.txt", est_late);
  // Frames 0-4 lost. The capture's poses within half a frame period of the frames: 1.99-2.31 s, 33;
  // 17 of them within 0.02 s of frames 5-9 (2.15-2.31 s).
  EXPECT_NEAR(rate_against(dir / "run"), 100.0 * 17 / 33, 0.01);
}

TEST(EvalCli, SharedKittiGroundTruthAgainstItselfIsZero) {
  WARDMAP_REQUIRE_DATA("kitti-odometry-03");
  const fs::path data = shared_data_dir() / "kitti-odometry-03";
  const nlohmann::json j = run_eval(data, data / "poses" / "03.txt", "sim3", scratch_dir());
  EXPECT_EQ(j["pairs"].get<int>(), 400);
  EXPECT_LT(j["ate"]["rmse"].get<double>(), 1e-6);
  EXPECT_NEAR(j["tracking_rate"].get<double>(), 100.0, 1e-9);
}

}  // namespace
}  // namespace wardmap::test
