// Least-squares alignment of two point sets (Umeyama 1991), the alignment of RUMI (1)-(3) and of
// EVALUATION.md: finds T minimising sum |dst_i - T(src_i)|^2 with T in Sim(3) or SE(3).
#pragma once

#include <Eigen/Core>

#include "slam/core/sim3.h"

namespace wardmap::slam {

// src and dst are 3xN with N >= 3 corresponding columns. Throws std::invalid_argument for fewer
// than 3 points or a degenerate (collinear / coincident) source set.
Sim3 umeyama_sim3(const Eigen::Matrix3Xd& src, const Eigen::Matrix3Xd& dst);
// The same with the scale fixed to 1.
Sim3 umeyama_se3(const Eigen::Matrix3Xd& src, const Eigen::Matrix3Xd& dst);

}  // namespace wardmap::slam
