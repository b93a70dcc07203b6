#include "slam/front/triangulation.h"

#include <Eigen/SVD>

namespace wardmap::slam {

std::optional<Eigen::Vector3d> triangulate_dlt(const Eigen::Vector3d& x1, const Eigen::Vector3d& x2, const SE3& T1,
                                               const SE3& T2) {
  Eigen::Matrix<double, 3, 4> P1, P2;
  P1 << T1.rotation_matrix(), T1.translation();
  P2 << T2.rotation_matrix(), T2.translation();
  Eigen::Matrix4d A;
  A.row(0) = x1.x() * P1.row(2) - P1.row(0);
  A.row(1) = x1.y() * P1.row(2) - P1.row(1);
  A.row(2) = x2.x() * P2.row(2) - P2.row(0);
  A.row(3) = x2.y() * P2.row(2) - P2.row(1);
  Eigen::JacobiSVD<Eigen::Matrix4d> svd(A, Eigen::ComputeFullV);
  const Eigen::Vector4d X = svd.matrixV().col(3);
  if (std::abs(X(3)) < 1e-12) return std::nullopt;
  return Eigen::Vector3d(X.head<3>() / X(3));
}

}  // namespace wardmap::slam
