#include "slam/io/trajectory_io.h"

#include <cstdio>
#include <limits>
#include <stdexcept>

#include "slam/core/errors.h"
#include "slam/io/text_file.h"

namespace wardmap::slam::io {

namespace fs = std::filesystem;

PoseFormat parse_pose_format(const std::string& name) {
  if (name == "auto") return PoseFormat::Auto;
  if (name == "tum") return PoseFormat::Tum;
  if (name == "kitti") return PoseFormat::Kitti;
  throw std::invalid_argument("unknown pose format '" + name + "' (allowed: auto, tum, kitti)");
}

SE3 checked_pose(const Eigen::Quaterniond& q, const Eigen::Vector3d& t, const fs::path& file, long line) {
  if (!(std::abs(q.norm() - 1.0) <= 1e-2))
    throw InputError(file.string(), "quaternion is not unit length (norm " + std::to_string(q.norm()) + ")", line);
  return SE3(q, t);  // normalised there
}

SE3 checked_pose(const Eigen::Matrix4d& T, const fs::path& file, long line) {
  const Eigen::Matrix3d R = T.topLeftCorner<3, 3>();
  const double det = R.determinant(), off = (R.transpose() * R - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff();
  if (!(std::abs(det - 1.0) <= 1e-2 && off <= 1e-2))
    throw InputError(file.string(),
                     "rotation block is not a rotation (determinant " + std::to_string(det) +
                         ", R^T R off the identity by " + std::to_string(off) + ")",
                     line);
  return SE3::from_matrix(T);
}

Trajectory read_trajectory(const fs::path& file, PoseFormat format) {
  Trajectory traj;
  double previous = -std::numeric_limits<double>::infinity();
  long index = 0;
  for_each_data_line(file, false, [&](long line, const std::vector<std::string>& tok) {
    if (format == PoseFormat::Auto) {
      if (tok.size() == 8) format = PoseFormat::Tum;
      else if (tok.size() == 12) format = PoseFormat::Kitti;
      else
        throw InputError(file.string(),
                         "cannot tell the pose format: expected 8 values (TUM) or 12 (KITTI), got " +
                             std::to_string(tok.size()), line);
    }
    if (format == PoseFormat::Tum) {
      if (tok.size() != 8)
        throw InputError(file.string(), "expected 8 values 'timestamp tx ty tz qx qy qz qw', got " +
                                            std::to_string(tok.size()), line);
      double v[8];
      for (int i = 0; i < 8; ++i) v[i] = parse_double(tok[i], file, line, "pose value");
      check_increasing(v[0], previous, file, line);
      previous = v[0];
      traj.push_back(v[0], checked_pose(Eigen::Quaterniond(v[7], v[4], v[5], v[6]), {v[1], v[2], v[3]}, file, line));
    } else {
      if (tok.size() != 12)
        throw InputError(file.string(), "expected 12 values (row-major 3x4 pose), got " + std::to_string(tok.size()), line);
      Eigen::Matrix4d T = Eigen::Matrix4d::Identity();
      for (int i = 0; i < 12; ++i) T(i / 4, i % 4) = parse_double(tok[i], file, line, "pose value");
      traj.push_back(static_cast<double>(index++), checked_pose(T, file, line));
    }
  });
  traj.indexed = (format == PoseFormat::Kitti);
  if (traj.empty()) throw InputError(file.string(), "no poses in the file");
  return traj;
}

std::string format_tum(const Trajectory& traj) {
  std::string out;
  char buf[256];
  for (size_t i = 0; i < traj.size(); ++i) {
    const auto& T = traj.poses[i];
    const auto& q = T.rotation();
    const auto& t = T.translation();
    std::snprintf(buf, sizeof buf, "%.6f %.9f %.9f %.9f %.9f %.9f %.9f %.9f\n", traj.timestamps[i], t.x(), t.y(), t.z(),
                  q.x(), q.y(), q.z(), q.w());
    out += buf;
  }
  return out;
}

std::string format_kitti(const Trajectory& traj) {
  std::string out;
  char buf[64];
  for (const auto& T : traj.poses) {
    const Eigen::Matrix4d M = T.matrix();
    for (int i = 0; i < 12; ++i) {
      std::snprintf(buf, sizeof buf, i == 11 ? "%.9e\n" : "%.9e ", M(i / 4, i % 4));
      out += buf;
    }
  }
  return out;
}

void write_tum(const fs::path& file, const Trajectory& traj) { write_file_atomic(file, format_tum(traj)); }
void write_kitti(const fs::path& file, const Trajectory& traj) { write_file_atomic(file, format_kitti(traj)); }

}  // namespace wardmap::slam::io
