#include "slam/core/camera.h"

#include <Eigen/LU>
#include <cmath>
#include <sstream>

namespace wardmap::slam {

std::optional<std::string> PinholeCamera::validate(std::string* parameter) const {
  std::ostringstream err;
  std::string bad;
  if (!(fx > 0) || !std::isfinite(fx)) bad = "fx", err << "fx must be positive (got " << fx << ")";
  else if (!(fy > 0) || !std::isfinite(fy)) bad = "fy", err << "fy must be positive (got " << fy << ")";
  else if (width <= 0 || height <= 0) bad = "size", err << "image size must be positive (got " << width << "x" << height << ")";
  else if (!(cx > 0 && cx < width)) bad = "cx", err << "cx must lie inside the image width " << width << " (got " << cx << ")";
  else if (!(cy > 0 && cy < height)) bad = "cy", err << "cy must lie inside the image height " << height << " (got " << cy << ")";
  else if (!std::isfinite(k1 + k2 + p1 + p2 + k3)) bad = "distortion", err << "distortion coefficients must be finite";
  if (parameter) *parameter = bad;
  if (bad.empty()) return std::nullopt;
  return err.str();
}

Eigen::Vector2d PinholeCamera::distort_normalized(const Eigen::Vector2d& xn) const {
  const double x = xn.x(), y = xn.y();
  const double r2 = x * x + y * y;
  const double radial = 1 + r2 * (k1 + r2 * (k2 + r2 * k3));
  return {x * radial + 2 * p1 * x * y + p2 * (r2 + 2 * x * x), y * radial + p1 * (r2 + 2 * y * y) + 2 * p2 * x * y};
}

// Jacobian of distort_normalized at xn.
static Eigen::Matrix2d distortion_jacobian(const PinholeCamera& c, const Eigen::Vector2d& xn) {
  const double x = xn.x(), y = xn.y();
  const double r2 = x * x + y * y;
  const double radial = 1 + r2 * (c.k1 + r2 * (c.k2 + r2 * c.k3));
  const double dradial_dr2 = c.k1 + r2 * (2 * c.k2 + 3 * r2 * c.k3);
  Eigen::Matrix2d J;
  J(0, 0) = radial + x * dradial_dr2 * 2 * x + 2 * c.p1 * y + c.p2 * 6 * x;
  J(0, 1) = x * dradial_dr2 * 2 * y + 2 * c.p1 * x + c.p2 * 2 * y;
  J(1, 0) = y * dradial_dr2 * 2 * x + c.p1 * 2 * x + 2 * c.p2 * y;
  J(1, 1) = radial + y * dradial_dr2 * 2 * y + c.p1 * 6 * y + 2 * c.p2 * x;
  return J;
}

Eigen::Vector2d PinholeCamera::undistort_normalized(const Eigen::Vector2d& xd) const {
  if (!has_distortion()) return xd;
  // Gauss-Newton on distort(x) = xd, starting from xd; converges in a few steps for real lenses.
  Eigen::Vector2d x = xd;
  for (int it = 0; it < 20; ++it) {
    const Eigen::Vector2d r = distort_normalized(x) - xd;
    if (r.squaredNorm() < 1e-24) break;
    x -= distortion_jacobian(*this, x).inverse() * r;
  }
  return x;
}

Eigen::Vector2d PinholeCamera::project(const Eigen::Vector3d& p) const {
  const Eigen::Vector2d xd = distort_normalized(p.head<2>() / p.z());
  return {fx * xd.x() + cx, fy * xd.y() + cy};
}

Eigen::Matrix<double, 2, 3> PinholeCamera::project_jacobian(const Eigen::Vector3d& p) const {
  const double iz = 1.0 / p.z();
  Eigen::Matrix<double, 2, 3> dn;  // d(x/z, y/z) / dp
  dn << iz, 0, -p.x() * iz * iz, 0, iz, -p.y() * iz * iz;
  const Eigen::Matrix2d K = Eigen::Vector2d(fx, fy).asDiagonal();
  return K * distortion_jacobian(*this, p.head<2>() * iz) * dn;
}

Eigen::Vector3d PinholeCamera::unproject(const Eigen::Vector2d& pixel) const {
  const Eigen::Vector2d xd((pixel.x() - cx) / fx, (pixel.y() - cy) / fy);
  const Eigen::Vector2d xn = undistort_normalized(xd);
  return {xn.x(), xn.y(), 1.0};
}

Eigen::Vector2d PinholeCamera::undistort_point(const Eigen::Vector2d& pixel) const {
  const Eigen::Vector3d ray = unproject(pixel);
  return {fx * ray.x() + cx, fy * ray.y() + cy};
}

}  // namespace wardmap::slam
