#include "mot/kalman_box_filter.h"

#include <Eigen/Cholesky>
#include <cmath>
#include <sstream>
#include <stdexcept>

namespace wardmap::mot {

Vector4d corners_to_xyah(const Vector4d& c) {
  const double w = c(2) - c(0), h = c(3) - c(1);
  return Vector4d(c(0) + 0.5 * w, c(1) + 0.5 * h, h > 0 ? w / h : 0.0, h);
}

Vector4d xyah_to_corners(const Vector4d& z) {
  const double w = z(2) * z(3), h = z(3);
  return Vector4d(z(0) - 0.5 * w, z(1) - 0.5 * h, z(0) + 0.5 * w, z(1) + 0.5 * h);
}

std::optional<std::string> KalmanBoxOptions::validate() const {
  std::ostringstream err;
  auto positive = [&](const char* name, double v) {
    if (err.tellp() == 0 && !(v > 0 && std::isfinite(v)))
      err << name << " must be positive and finite (got " << v << ")";
  };
  positive("std_weight_position", std_weight_position);
  positive("std_weight_velocity", std_weight_velocity);
  positive("std_aspect", std_aspect);
  positive("std_aspect_velocity", std_aspect_velocity);
  if (err.tellp() == 0) return std::nullopt;
  return err.str();
}

KalmanBoxFilter::KalmanBoxFilter(const KalmanBoxOptions& options) : options_(options) {
  if (auto err = options_.validate()) throw std::invalid_argument("KalmanBoxOptions: " + *err);
}

Vector4d KalmanBoxFilter::measurement_std(double h) const {
  const double p = options_.std_weight_position * h;
  return Vector4d(p, p, options_.std_aspect, p);
}

BoxState KalmanBoxFilter::initiate(const Vector4d& z) const {
  BoxState s;
  s.mean.head<4>() = z;
  s.mean.tail<4>().setZero();
  const double h = z(3), p = options_.std_weight_position * h, v = options_.std_weight_velocity * h;
  Vector8d std;
  std << 2 * p, 2 * p, options_.std_aspect, 2 * p, 10 * v, 10 * v, 10 * options_.std_aspect_velocity, 10 * v;
  s.covariance = std.array().square().matrix().asDiagonal();
  return s;
}

void KalmanBoxFilter::predict(BoxState& s, double dt) const {
  Matrix8d F = Matrix8d::Identity();
  for (int i = 0; i < 4; ++i) F(i, 4 + i) = dt;
  const double h = s.mean(3), p = options_.std_weight_position * h, v = options_.std_weight_velocity * h;
  Vector8d std;
  std << p, p, options_.std_aspect, p, v, v, options_.std_aspect_velocity, v;
  // Process noise grows linearly with the elapsed time (a random walk on each component).
  const Matrix8d Q = (std.array().square() * std::max(dt, 0.0)).matrix().asDiagonal();
  s.mean = F * s.mean;
  s.covariance = F * s.covariance * F.transpose() + Q;
}

void KalmanBoxFilter::project(const BoxState& s, Vector4d* mean, Matrix4d* cov) const {
  *mean = s.mean.head<4>();
  const Vector4d r = measurement_std(s.mean(3));
  *cov = s.covariance.topLeftCorner<4, 4>();
  cov->diagonal() += r.array().square().matrix();
}

void KalmanBoxFilter::update(BoxState& s, const Vector4d& z) const {
  Vector4d zm;
  Matrix4d S;
  project(s, &zm, &S);
  // K = P H^T S^-1, with H = [I 0]: P H^T is the left 8x4 block of P.
  const Eigen::Matrix<double, 8, 4> PHt = s.covariance.leftCols<4>();
  const Eigen::Matrix<double, 4, 8> Kt = S.llt().solve(PHt.transpose());
  s.mean += Kt.transpose() * (z - zm);
  s.covariance -= Kt.transpose() * S * Kt;
  s.covariance = 0.5 * (s.covariance + s.covariance.transpose());
}

double KalmanBoxFilter::gating_distance(const BoxState& s, const Vector4d& z, bool position_only) const {
  Vector4d zm;
  Matrix4d S;
  project(s, &zm, &S);
  const Vector4d d = z - zm;
  if (position_only) {
    const Eigen::Vector2d d2 = d.head<2>();
    return d2.dot(S.topLeftCorner<2, 2>().llt().solve(d2));
  }
  return d.dot(S.llt().solve(d));
}

}  // namespace wardmap::mot
