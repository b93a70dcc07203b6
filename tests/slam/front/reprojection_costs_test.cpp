#include "slam/front/reprojection_costs.h"

#include <gtest/gtest.h>

namespace wardmap::slam {

namespace {

const PinholeIntrinsics kK{525, 520, 319.5, 239.5, 42.0};

// Central differences of a cost function over its parameter blocks (ambient coordinates).
std::vector<Eigen::MatrixXd> numeric_jacobians(const ceres::CostFunction& f, std::vector<std::vector<double>> params) {
  const int m = f.num_residuals();
  std::vector<Eigen::MatrixXd> J;
  for (size_t b = 0; b < params.size(); ++b) {
    Eigen::MatrixXd Jb(m, static_cast<int>(params[b].size()));
    for (size_t k = 0; k < params[b].size(); ++k) {
      const double h = 1e-6;
      auto eval = [&](double delta) {
        auto p = params;
        p[b][k] += delta;
        std::vector<const double*> ptrs;
        for (auto& v : p) ptrs.push_back(v.data());
        Eigen::VectorXd r(m);
        f.Evaluate(ptrs.data(), r.data(), nullptr);
        return r;
      };
      Jb.col(static_cast<int>(k)) = (eval(h) - eval(-h)) / (2 * h);
    }
    J.push_back(Jb);
  }
  return J;
}

std::vector<Eigen::MatrixXd> analytic_jacobians(const ceres::CostFunction& f, std::vector<std::vector<double>> params,
                                                Eigen::VectorXd* residual) {
  const int m = f.num_residuals();
  std::vector<Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>> J;
  std::vector<double*> jp;
  std::vector<const double*> ptrs;
  for (auto& v : params) {
    J.emplace_back(m, static_cast<int>(v.size()));
    ptrs.push_back(v.data());
  }
  for (auto& j : J) jp.push_back(j.data());
  residual->resize(m);
  EXPECT_TRUE(f.Evaluate(ptrs.data(), residual->data(), jp.data()));
  return {J.begin(), J.end()};
}

std::vector<double> quaternion(const Eigen::Quaterniond& q) { return {q.x(), q.y(), q.z(), q.w()}; }

}  // namespace

TEST(ReprojectionCosts, PoseOnlyJacobiansMatchFiniteDifferences) {
  const Eigen::Quaterniond q = Eigen::Quaterniond(Eigen::AngleAxisd(0.3, Eigen::Vector3d(1, 2, 3).normalized()));
  const std::vector<std::vector<double>> params = {quaternion(q), {0.1, -0.2, 0.3}};
  for (bool stereo : {false, true}) {
    std::unique_ptr<ceres::CostFunction> f(
        stereo ? PoseReprojectionCost<true>::create(kK, {0.4, -0.3, 3.0}, {300, 250}, 290, 0.8)
               : PoseReprojectionCost<false>::create(kK, {0.4, -0.3, 3.0}, {300, 250}, -1, 0.8));
    Eigen::VectorXd r;
    const auto Ja = analytic_jacobians(*f, params, &r);
    const auto Jn = numeric_jacobians(*f, params);
    for (size_t b = 0; b < Ja.size(); ++b) EXPECT_LT((Ja[b] - Jn[b]).norm(), 1e-4 * (1 + Jn[b].norm())) << b;
  }
}

TEST(ReprojectionCosts, BundleAdjustmentJacobiansMatchFiniteDifferences) {
  const Eigen::Quaterniond q = Eigen::Quaterniond(Eigen::AngleAxisd(-0.2, Eigen::Vector3d(0, 1, 0.2).normalized()));
  const std::vector<std::vector<double>> params = {quaternion(q), {0.05, 0.1, -0.2}, {-0.5, 0.2, 2.5}};
  for (bool stereo : {false, true}) {
    std::unique_ptr<ceres::CostFunction> f(stereo ? ReprojectionCost<true>::create(kK, {310, 230}, 300, 1.0)
                                                  : ReprojectionCost<false>::create(kK, {310, 230}, -1, 1.0));
    Eigen::VectorXd r;
    const auto Ja = analytic_jacobians(*f, params, &r);
    const auto Jn = numeric_jacobians(*f, params);
    for (size_t b = 0; b < Ja.size(); ++b) EXPECT_LT((Ja[b] - Jn[b]).norm(), 1e-4 * (1 + Jn[b].norm())) << b;
  }
}

TEST(ReprojectionCosts, ResidualIsZeroAtTheTrueProjection) {
  const Eigen::Vector3d pw(0.3, -0.1, 2.0);
  const Eigen::Quaterniond q = Eigen::Quaterniond(Eigen::AngleAxisd(0.1, Eigen::Vector3d::UnitY()));
  const Eigen::Vector3d t(0.1, 0.0, 0.2);
  const Eigen::Vector3d pc = q * pw + t;
  const Eigen::Vector2d px(kK.fx * pc.x() / pc.z() + kK.cx, kK.fy * pc.y() / pc.z() + kK.cy);
  const double ur = px.x() - kK.bf / pc.z();
  std::unique_ptr<ceres::CostFunction> f(PoseReprojectionCost<true>::create(kK, pw, px, ur, 1.0));
  const std::vector<double> qv = quaternion(q), tv = {t.x(), t.y(), t.z()};
  const double* p[] = {qv.data(), tv.data()};
  double r[3];
  ASSERT_TRUE(f->Evaluate(p, r, nullptr));
  EXPECT_NEAR(r[0], 0, 1e-9);
  EXPECT_NEAR(r[1], 0, 1e-9);
  EXPECT_NEAR(r[2], 0, 1e-9);
}

}  // namespace wardmap::slam

namespace wardmap::slam {

// The analytic Jacobian of the pose-only cost against central differences, mono and stereo,
// at delta = 0 and at a small non-zero delta.
TEST(PosePerturbationCost, JacobianMatchesFiniteDifferences) {
  const PinholeIntrinsics K{525, 520, 319.5, 239.5, 40.0};
  const SE3 T0(Eigen::Quaterniond(Eigen::AngleAxisd(0.3, Eigen::Vector3d(1, 2, 3).normalized())),
               Eigen::Vector3d(0.1, -0.2, 0.3));
  const PoseObservation o{{0.4, -0.3, 3.0}, {300, 250}, 290, 0.8};
  const PosePerturbationCost<3> stereo(K, T0, o);
  PoseObservation om = o;
  om.right_u = -1;
  const PosePerturbationCost<2> mono(K, T0, om);
  for (const ceres::CostFunction* f : {static_cast<const ceres::CostFunction*>(&stereo),
                                       static_cast<const ceres::CostFunction*>(&mono)}) {
    const int m = f->num_residuals();
    for (double scale : {0.0, 1e-3}) {
      double delta[6] = {scale, -scale, 2 * scale, scale, scale, -scale};
      const double* params[] = {delta};
      std::vector<double> r(static_cast<size_t>(m)), J(static_cast<size_t>(6 * m));
      double* jac[] = {J.data()};
      ASSERT_TRUE(f->Evaluate(params, r.data(), jac));
      for (int k = 0; k < 6; ++k) {
        double dp[6], dm[6];
        std::copy(delta, delta + 6, dp);
        std::copy(delta, delta + 6, dm);
        dp[k] += 1e-6;
        dm[k] -= 1e-6;
        std::vector<double> rp(static_cast<size_t>(m)), rm(static_cast<size_t>(m));
        const double* pp[] = {dp};
        const double* pm[] = {dm};
        f->Evaluate(pp, rp.data(), nullptr);
        f->Evaluate(pm, rm.data(), nullptr);
        for (int i = 0; i < m; ++i) {
          const double numeric = (rp[static_cast<size_t>(i)] - rm[static_cast<size_t>(i)]) / 2e-6;
          // Exact at delta = 0; at a small delta the left-perturbation Jacobian is off by O(delta) x the
          // entries (which reach a few hundred here).
          EXPECT_NEAR(J[static_cast<size_t>(i * 6 + k)], numeric, scale == 0 ? 1e-4 : 0.5)
              << "residual " << i << " parameter " << k << " delta scale " << scale;
        }
      }
    }
  }
}

}  // namespace wardmap::slam

namespace wardmap::slam {

// The hand-written bundle-adjustment Jacobians equal the automatic ones of ReprojectionCost (same
// ambient coordinates), mono and stereo, at unit and non-unit quaternions; a wrong derivative term
// is off by far more than the tolerance.
TEST(BundleReprojectionCost, JacobiansEqualAutomaticDifferentiation) {
  std::srand(7);
  auto rnd = [] { return 2.0 * std::rand() / RAND_MAX - 1.0; };
  for (int trial = 0; trial < 20; ++trial) {
    Eigen::Quaterniond q(Eigen::AngleAxisd(1.5 * rnd(), Eigen::Vector3d(rnd(), rnd(), rnd()).normalized()));
    if (trial % 4 == 3) q.coeffs() *= 1.1;  // Ceres may evaluate off the unit sphere
    const std::vector<std::vector<double>> params = {
        quaternion(q), {0.3 * rnd(), 0.3 * rnd(), 0.3 * rnd()}, {rnd(), rnd(), 0.5 * rnd()}};
    std::vector<double> pose = params[0];
    pose.insert(pose.end(), params[1].begin(), params[1].end());
    // Keep the point in front of the camera.
    Eigen::Vector3d pc = q.normalized() * Eigen::Vector3d(params[2][0], params[2][1], params[2][2]) +
                         Eigen::Vector3d(params[1][0], params[1][1], params[1][2]);
    if (pc.z() < 0.5) continue;
    const Eigen::Vector2d px(300 + 40 * rnd(), 240 + 40 * rnd());
    for (bool stereo : {false, true}) {
      const double ur = stereo ? px.x() - 20 : -1;
      std::unique_ptr<ceres::CostFunction> automatic(stereo ? ReprojectionCost<true>::create(kK, px, ur, 0.7)
                                                            : ReprojectionCost<false>::create(kK, px, ur, 0.7));
      std::unique_ptr<ceres::CostFunction> analytic(
          stereo ? static_cast<ceres::CostFunction*>(new BundleReprojectionCost<3>(kK, px, ur, 0.7))
                 : new BundleReprojectionCost<2>(kK, px, ur, 0.7));
      Eigen::VectorXd r_auto, r_analytic;
      const auto Jauto = analytic_jacobians(*automatic, params, &r_auto);
      const auto Jan = analytic_jacobians(*analytic, {pose, params[2]}, &r_analytic);
      EXPECT_LT((r_auto - r_analytic).norm(), 1e-9 * (1 + r_auto.norm()));
      const Eigen::MatrixXd Jq = Jan[0].leftCols(4), Jt = Jan[0].rightCols(3);
      EXPECT_LT((Jauto[0] - Jq).norm(), 1e-9 * (1 + Jauto[0].norm())) << "trial " << trial << " q";
      EXPECT_LT((Jauto[1] - Jt).norm(), 1e-9 * (1 + Jauto[1].norm())) << "trial " << trial << " t";
      EXPECT_LT((Jauto[2] - Jan[1]).norm(), 1e-9 * (1 + Jauto[2].norm())) << "trial " << trial << " point";
    }
  }
}

}  // namespace wardmap::slam
