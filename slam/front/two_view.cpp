#include "slam/front/two_view.h"

#include <Eigen/SVD>
#include <algorithm>
#include <cmath>
#include <opencv2/calib3d.hpp>
#include <opencv2/core/eigen.hpp>
#include <random>

#include "slam/front/triangulation.h"

namespace wardmap::slam {

namespace {

constexpr double kChi2OneDof = 3.841;  // 95 % of chi2 with 1 dof (point-to-epipolar-line distance)
constexpr double kChi2TwoDof = 5.991;  // 95 % of chi2 with 2 dof (transfer error)

// Hartley normalisation: centroid to the origin, mean absolute deviation 1 on each axis.
Eigen::Matrix3d normalise(const std::vector<Eigen::Vector2d>& p, std::vector<Eigen::Vector2d>& out) {
  Eigen::Vector2d mean = Eigen::Vector2d::Zero();
  for (const auto& x : p) mean += x;
  mean /= static_cast<double>(p.size());
  Eigen::Vector2d dev = Eigen::Vector2d::Zero();
  for (const auto& x : p) dev += (x - mean).cwiseAbs();
  dev /= static_cast<double>(p.size());
  const double sx = dev.x() > 0 ? 1.0 / dev.x() : 1.0, sy = dev.y() > 0 ? 1.0 / dev.y() : 1.0;
  out.resize(p.size());
  for (size_t i = 0; i < p.size(); ++i) out[i] = {(p[i].x() - mean.x()) * sx, (p[i].y() - mean.y()) * sy};
  Eigen::Matrix3d T;
  T << sx, 0, -mean.x() * sx, 0, sy, -mean.y() * sy, 0, 0, 1;
  return T;
}

Eigen::Matrix<double, 9, 1> null_vector(const Eigen::MatrixXd& A) {
  Eigen::JacobiSVD<Eigen::MatrixXd> svd(A, Eigen::ComputeFullV);
  return svd.matrixV().col(8);
}

struct Motion {
  Eigen::Matrix3d R;
  Eigen::Vector3d t;
};

struct MotionCheck {
  int good = 0;
  double parallax_deg = 0;
  std::vector<Eigen::Vector3d> points;
  std::vector<char> triangulated;
};

// Triangulates the inliers under motion (R, t) and counts the points in front of both cameras with a
// small reprojection error (ORB-SLAM's CheckRT).
MotionCheck check_motion(const Motion& m, const std::vector<Eigen::Vector2d>& p1, const std::vector<Eigen::Vector2d>& p2,
                         const std::vector<char>& inliers, const PinholeCamera& cam, double th2) {
  MotionCheck c;
  c.points.assign(p1.size(), Eigen::Vector3d::Zero());
  c.triangulated.assign(p1.size(), 0);
  const SE3 T1, T2(m.R, m.t);
  const Eigen::Vector3d o2 = -m.R.transpose() * m.t;
  std::vector<double> cos_parallax;
  auto ray = [&cam](const Eigen::Vector2d& p) {
    return Eigen::Vector3d((p.x() - cam.cx) / cam.fx, (p.y() - cam.cy) / cam.fy, 1);
  };
  auto reprojection2 = [&cam](const Eigen::Vector3d& X, const Eigen::Vector2d& p) {
    const Eigen::Vector2d u(cam.fx * X.x() / X.z() + cam.cx, cam.fy * X.y() / X.z() + cam.cy);
    return (u - p).squaredNorm();
  };
  for (size_t i = 0; i < p1.size(); ++i) {
    if (!inliers[i]) continue;
    const auto X = triangulate_dlt(ray(p1[i]), ray(p2[i]), T1, T2);
    if (!X || !X->allFinite()) continue;
    const double cosp = parallax_cos(*X, Eigen::Vector3d::Zero(), o2);
    const Eigen::Vector3d X2 = m.R * *X + m.t;
    if ((X->z() <= 0 || X2.z() <= 0) && cosp < 0.99998) continue;
    if (X->z() <= 0 || X2.z() <= 0) continue;
    if (reprojection2(*X, p1[i]) > th2 || reprojection2(X2, p2[i]) > th2) continue;
    cos_parallax.push_back(cosp);
    c.points[i] = *X;
    ++c.good;
    if (cosp < 0.99998) c.triangulated[i] = 1;
  }
  if (!cos_parallax.empty()) {
    std::sort(cos_parallax.begin(), cos_parallax.end());
    const size_t idx = std::min<size_t>(50, cos_parallax.size() - 1);
    c.parallax_deg = std::acos(std::clamp(cos_parallax[idx], -1.0, 1.0)) * 180.0 / M_PI;
  }
  return c;
}

// Picks the motion with the most good points if it is unambiguous, well triangulated and has parallax.
std::optional<TwoViewReconstruction> choose_motion(const std::vector<Motion>& motions,
                                                   const std::vector<Eigen::Vector2d>& p1,
                                                   const std::vector<Eigen::Vector2d>& p2, const std::vector<char>& inliers,
                                                   const PinholeCamera& cam, const TwoViewOptions& o) {
  if (motions.empty()) return std::nullopt;
  const int n_inliers = static_cast<int>(std::count(inliers.begin(), inliers.end(), 1));
  std::vector<MotionCheck> checks;
  for (const auto& m : motions) checks.push_back(check_motion(m, p1, p2, inliers, cam, 4.0 * o.sigma * o.sigma));
  size_t best = 0;
  for (size_t k = 1; k < checks.size(); ++k)
    if (checks[k].good > checks[best].good) best = k;
  const int max_good = checks[best].good;
  int similar = 0;
  for (const auto& c : checks) similar += c.good > o.ambiguity_ratio * max_good ? 1 : 0;
  const int min_good = std::max(static_cast<int>(o.min_good_ratio * n_inliers), o.min_triangulated);
  if (max_good < min_good || similar > 1 || checks[best].parallax_deg < o.min_parallax_deg) return std::nullopt;
  TwoViewReconstruction r;
  r.T_21 = SE3(motions[best].R, motions[best].t);
  r.points = std::move(checks[best].points);
  r.triangulated = std::move(checks[best].triangulated);
  r.good = static_cast<int>(std::count(r.triangulated.begin(), r.triangulated.end(), 1));
  r.parallax_deg = checks[best].parallax_deg;
  if (r.good < o.min_triangulated) return std::nullopt;
  return r;
}

Eigen::Matrix3d orthonormal(const Eigen::Matrix3d& R) {
  Eigen::JacobiSVD<Eigen::Matrix3d> svd(R, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Eigen::Matrix3d out = svd.matrixU() * svd.matrixV().transpose();
  return out.determinant() < 0 ? Eigen::Matrix3d(-out) : out;
}

Eigen::Matrix3d intrinsics(const PinholeCamera& c) {
  Eigen::Matrix3d K;
  K << c.fx, 0, c.cx, 0, c.fy, c.cy, 0, 0, 1;
  return K;
}

// The four motions of an essential matrix (Hartley & Zisserman, Result 9.19).
std::vector<Motion> motions_from_fundamental(const Eigen::Matrix3d& F21, const PinholeCamera& cam) {
  const Eigen::Matrix3d K = intrinsics(cam);
  const Eigen::Matrix3d E = K.transpose() * F21 * K;
  Eigen::JacobiSVD<Eigen::Matrix3d> svd(E, Eigen::ComputeFullU | Eigen::ComputeFullV);
  const Eigen::Matrix3d &U = svd.matrixU(), &V = svd.matrixV();
  Eigen::Matrix3d W;
  W << 0, -1, 0, 1, 0, 0, 0, 0, 1;
  Eigen::Matrix3d R1 = U * W * V.transpose(), R2 = U * W.transpose() * V.transpose();
  if (R1.determinant() < 0) R1 = -R1;
  if (R2.determinant() < 0) R2 = -R2;
  const Eigen::Vector3d t = U.col(2).normalized();
  return {{R1, t}, {R1, -t}, {R2, t}, {R2, -t}};
}

// The motions of a homography between calibrated views (OpenCV's analytical decomposition, Malis &
// Vargas 2007); the cheirality check in check_motion removes the mirrored ones.
std::vector<Motion> motions_from_homography(const Eigen::Matrix3d& H21, const PinholeCamera& cam) {
  cv::Mat H, K;
  cv::eigen2cv(H21, H);
  cv::eigen2cv(intrinsics(cam), K);
  std::vector<cv::Mat> Rs, ts, ns;
  cv::decomposeHomographyMat(H, K, Rs, ts, ns);
  std::vector<Motion> out;
  for (size_t k = 0; k < Rs.size(); ++k) {
    Eigen::Matrix3d R;
    Eigen::Vector3d t;
    cv::cv2eigen(Rs[k], R);
    cv::cv2eigen(ts[k], t);
    if (t.norm() < 1e-12) continue;  // pure rotation: no baseline
    out.push_back({orthonormal(R), t.normalized()});
  }
  return out;
}

}  // namespace

Eigen::Matrix3d homography_dlt(const std::vector<Eigen::Vector2d>& p1, const std::vector<Eigen::Vector2d>& p2) {
  std::vector<Eigen::Vector2d> n1, n2;
  const Eigen::Matrix3d T1 = normalise(p1, n1), T2 = normalise(p2, n2);
  Eigen::MatrixXd A(2 * n1.size(), 9);
  for (size_t i = 0; i < n1.size(); ++i) {
    const double u1 = n1[i].x(), v1 = n1[i].y(), u2 = n2[i].x(), v2 = n2[i].y();
    A.row(static_cast<Eigen::Index>(2 * i)) << 0, 0, 0, -u1, -v1, -1, v2 * u1, v2 * v1, v2;
    A.row(static_cast<Eigen::Index>(2 * i + 1)) << u1, v1, 1, 0, 0, 0, -u2 * u1, -u2 * v1, -u2;
  }
  const auto h = null_vector(A);
  Eigen::Matrix3d Hn;
  Hn << h(0), h(1), h(2), h(3), h(4), h(5), h(6), h(7), h(8);
  return T2.inverse() * Hn * T1;
}

Eigen::Matrix3d fundamental_8point(const std::vector<Eigen::Vector2d>& p1, const std::vector<Eigen::Vector2d>& p2) {
  std::vector<Eigen::Vector2d> n1, n2;
  const Eigen::Matrix3d T1 = normalise(p1, n1), T2 = normalise(p2, n2);
  Eigen::MatrixXd A(std::max<size_t>(n1.size(), 9), 9);
  A.setZero();
  for (size_t i = 0; i < n1.size(); ++i) {
    const double u1 = n1[i].x(), v1 = n1[i].y(), u2 = n2[i].x(), v2 = n2[i].y();
    A.row(static_cast<Eigen::Index>(i)) << u2 * u1, u2 * v1, u2, v2 * u1, v2 * v1, v2, u1, v1, 1;
  }
  const auto f = null_vector(A);
  Eigen::Matrix3d Fn;
  Fn << f(0), f(1), f(2), f(3), f(4), f(5), f(6), f(7), f(8);
  Eigen::JacobiSVD<Eigen::Matrix3d> svd(Fn, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Eigen::Vector3d s = svd.singularValues();
  s(2) = 0;
  Fn = svd.matrixU() * s.asDiagonal() * svd.matrixV().transpose();
  return T2.transpose() * Fn * T1;
}

double score_homography(const Eigen::Matrix3d& H21, const std::vector<Eigen::Vector2d>& p1,
                        const std::vector<Eigen::Vector2d>& p2, double sigma, std::vector<char>& inliers) {
  const Eigen::Matrix3d H12 = H21.inverse();
  const double inv_s2 = 1.0 / (sigma * sigma);
  double score = 0;
  inliers.assign(p1.size(), 0);
  for (size_t i = 0; i < p1.size(); ++i) {
    const Eigen::Vector3d a = H12 * p2[i].homogeneous(), b = H21 * p1[i].homogeneous();
    if (std::abs(a.z()) < 1e-12 || std::abs(b.z()) < 1e-12) continue;
    const double chi1 = (p1[i] - a.hnormalized()).squaredNorm() * inv_s2;
    const double chi2 = (p2[i] - b.hnormalized()).squaredNorm() * inv_s2;
    if (chi1 > kChi2TwoDof || chi2 > kChi2TwoDof) continue;
    score += (kChi2TwoDof - chi1) + (kChi2TwoDof - chi2);
    inliers[i] = 1;
  }
  return score;
}

double score_fundamental(const Eigen::Matrix3d& F21, const std::vector<Eigen::Vector2d>& p1,
                         const std::vector<Eigen::Vector2d>& p2, double sigma, std::vector<char>& inliers) {
  const double inv_s2 = 1.0 / (sigma * sigma);
  double score = 0;
  inliers.assign(p1.size(), 0);
  for (size_t i = 0; i < p1.size(); ++i) {
    const Eigen::Vector3d x1 = p1[i].homogeneous(), x2 = p2[i].homogeneous();
    const Eigen::Vector3d l2 = F21 * x1, l1 = F21.transpose() * x2;
    const double n2 = l2.head<2>().squaredNorm(), n1 = l1.head<2>().squaredNorm();
    if (n1 < 1e-24 || n2 < 1e-24) continue;
    const double chi2 = std::pow(l2.dot(x2), 2) / n2 * inv_s2;
    const double chi1 = std::pow(l1.dot(x1), 2) / n1 * inv_s2;
    if (chi1 > kChi2OneDof || chi2 > kChi2OneDof) continue;
    // Scored with the 2-dof threshold so that H and F scores are comparable (as ORB-SLAM does).
    score += (kChi2TwoDof - chi1) + (kChi2TwoDof - chi2);
    inliers[i] = 1;
  }
  return score;
}

std::optional<TwoViewReconstruction> reconstruct_two_views(const std::vector<Eigen::Vector2d>& p1,
                                                           const std::vector<Eigen::Vector2d>& p2,
                                                           const PinholeCamera& camera, const TwoViewOptions& o) {
  const size_t n = p1.size();
  if (n < 8 || p2.size() != n) return std::nullopt;
  std::mt19937_64 rng(o.seed);
  std::vector<size_t> order(n);
  double best_h = -1, best_f = -1;
  Eigen::Matrix3d H = Eigen::Matrix3d::Identity(), F = Eigen::Matrix3d::Zero();
  std::vector<char> in_h, in_f, tmp;
  std::vector<Eigen::Vector2d> s1(8), s2(8);
  for (int it = 0; it < o.ransac_iterations; ++it) {
    // The same minimal set of 8 pairs for both models (partial Fisher-Yates shuffle).
    for (size_t i = 0; i < n; ++i) order[i] = i;
    for (size_t k = 0; k < 8; ++k) {
      const size_t j = k + static_cast<size_t>(rng() % (n - k));
      std::swap(order[k], order[j]);
      s1[k] = p1[order[k]];
      s2[k] = p2[order[k]];
    }
    const Eigen::Matrix3d h = homography_dlt(s1, s2);
    const double sh = score_homography(h, p1, p2, o.sigma, tmp);
    if (sh > best_h) best_h = sh, H = h, in_h = tmp;
    const Eigen::Matrix3d f = fundamental_8point(s1, s2);
    const double sf = score_fundamental(f, p1, p2, o.sigma, tmp);
    if (sf > best_f) best_f = sf, F = f, in_f = tmp;
  }
  // One refit of each model on its inliers, kept when it scores better.
  auto refit = [&](bool homography) {
    std::vector<Eigen::Vector2d> a, b;
    const std::vector<char>& in = homography ? in_h : in_f;
    for (size_t i = 0; i < n; ++i)
      if (in[i]) a.push_back(p1[i]), b.push_back(p2[i]);
    if (a.size() < 8) return;
    if (homography) {
      const Eigen::Matrix3d h = homography_dlt(a, b);
      const double sh = score_homography(h, p1, p2, o.sigma, tmp);
      if (sh > best_h) best_h = sh, H = h, in_h = tmp;
    } else {
      const Eigen::Matrix3d f = fundamental_8point(a, b);
      const double sf = score_fundamental(f, p1, p2, o.sigma, tmp);
      if (sf > best_f) best_f = sf, F = f, in_f = tmp;
    }
  };
  refit(true);
  refit(false);
  if (best_h <= 0 && best_f <= 0) return std::nullopt;
  const double share = best_h / (best_h + best_f);
  const bool use_h = share > o.homography_share;
  auto r = use_h ? choose_motion(motions_from_homography(H, camera), p1, p2, in_h, camera, o)
                 : choose_motion(motions_from_fundamental(F, camera), p1, p2, in_f, camera, o);
  if (!r) return std::nullopt;
  r->homography = use_h;
  r->homography_share = share;
  return r;
}

}  // namespace wardmap::slam
