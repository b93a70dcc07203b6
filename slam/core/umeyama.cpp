#include "slam/core/umeyama.h"

#include <Eigen/SVD>
#include <stdexcept>
#include <string>

namespace wardmap::slam {

namespace {

Sim3 umeyama(const Eigen::Matrix3Xd& src, const Eigen::Matrix3Xd& dst, bool with_scale) {
  const Eigen::Index n = src.cols();
  if (n != dst.cols()) throw std::invalid_argument("umeyama: point sets differ in size");
  if (n < 3) throw std::invalid_argument("umeyama: needs at least 3 point pairs, got " + std::to_string(n));
  const Eigen::Vector3d mu_s = src.rowwise().mean(), mu_d = dst.rowwise().mean();
  const Eigen::Matrix3Xd s0 = src.colwise() - mu_s, d0 = dst.colwise() - mu_d;
  const double var_s = s0.squaredNorm() / static_cast<double>(n);
  if (var_s < 1e-18) throw std::invalid_argument("umeyama: source points coincide");
  const Eigen::Matrix3d sigma = d0 * s0.transpose() / static_cast<double>(n);
  Eigen::JacobiSVD<Eigen::Matrix3d> svd(sigma, Eigen::ComputeFullU | Eigen::ComputeFullV);
  const Eigen::Vector3d& sv = svd.singularValues();
  if (sv(1) < 1e-12 * std::max(1.0, sv(0)))
    throw std::invalid_argument("umeyama: points are collinear, rotation is undetermined");
  Eigen::Vector3d S = Eigen::Vector3d::Ones();
  if (svd.matrixU().determinant() * svd.matrixV().determinant() < 0) S(2) = -1;
  const Eigen::Matrix3d R = svd.matrixU() * S.asDiagonal() * svd.matrixV().transpose();
  const double scale = with_scale ? sv.dot(S) / var_s : 1.0;
  const Eigen::Vector3d t = mu_d - scale * R * mu_s;
  return Sim3(scale, Eigen::Quaterniond(R), t);
}

}  // namespace

Sim3 umeyama_sim3(const Eigen::Matrix3Xd& src, const Eigen::Matrix3Xd& dst) { return umeyama(src, dst, true); }
Sim3 umeyama_se3(const Eigen::Matrix3Xd& src, const Eigen::Matrix3Xd& dst) { return umeyama(src, dst, false); }

}  // namespace wardmap::slam
