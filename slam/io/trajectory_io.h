// Pose files: TUM (`timestamp tx ty tz qx qy qz qw`) and KITTI (12 numbers, row-major 3x4).
#pragma once

#include <filesystem>
#include <string>

#include "slam/core/trajectory.h"

namespace wardmap::slam::io {

enum class PoseFormat { Auto, Tum, Kitti };

PoseFormat parse_pose_format(const std::string& name);  // "auto" | "tum" | "kitti"; throws std::invalid_argument

// Reads a pose file; Auto decides by the number of values on the first data line (8 TUM, 12 KITTI).
// KITTI files give an indexed trajectory (timestamps = frame index). Throws InputError naming the
// file and line for a malformed line or a non-increasing timestamp.
// A pose as a dataset file gives it, checked: a unit quaternion (norm within 1 %), or a 4x4 / 3x4
// matrix whose rotation block is one (R^T R within 0.01 of the identity, determinant +1). Throws
// InputError naming the file and line (0: the file alone).
SE3 checked_pose(const Eigen::Quaterniond& q, const Eigen::Vector3d& t, const std::filesystem::path& file, long line);
SE3 checked_pose(const Eigen::Matrix4d& T, const std::filesystem::path& file, long line);

Trajectory read_trajectory(const std::filesystem::path& file, PoseFormat format = PoseFormat::Auto);

std::string format_tum(const Trajectory& traj);
std::string format_kitti(const Trajectory& traj);
// Written atomically (temporary name, then rename).
void write_tum(const std::filesystem::path& file, const Trajectory& traj);
void write_kitti(const std::filesystem::path& file, const Trajectory& traj);

}  // namespace wardmap::slam::io
