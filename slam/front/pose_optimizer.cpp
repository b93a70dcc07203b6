#include "slam/front/pose_optimizer.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <Eigen/Cholesky>

#include "slam/front/reprojection_costs.h"

namespace wardmap::slam {

namespace {

using Matrix6d = Eigen::Matrix<double, 6, 6>;

// Huber's rho on a squared whitened error s with threshold b (= a^2, a chi2 value), as
// ceres::HuberLoss(sqrt(b)): s inside, 2 sqrt(b s) - b outside. `weight` gets rho'(s), the factor of
// the observation in iteratively reweighted least squares.
double huber(double s, double b, double* weight) {
  if (s <= b) {
    *weight = 1.0;
    return s;
  }
  const double r = std::sqrt(b * s);
  *weight = b / r;  // sqrt(b / s)
  return 2.0 * r - b;
}

// The observations used in one round, with the robust threshold of each (0 = plain least squares).
struct ActiveObservation {
  const PoseObservation* o;
  double huber_b;
};

// Whitened residual of one observation whose point lies at `pc` in the camera (pc.z() > 0): 2 rows,
// or 3 with the virtual right coordinate. With `J`, its Jacobian for a left perturbation
// T <- exp(delta) T: d(pixel)/d(pc) times d(pc)/d(delta) = [I | -[pc]x] (exact at delta = 0).
int whitened_residual(const Eigen::Vector3d& pc, const PoseObservation& o, const PinholeIntrinsics& k,
                      Eigen::Vector3d* r, Eigen::Matrix<double, 3, 6>* J) {
  const double iz = 1.0 / pc.z(), s = o.inv_sigma;
  const double u = k.fx * pc.x() * iz + k.cx, v = k.fy * pc.y() * iz + k.cy;
  const bool stereo = o.right_u >= 0;
  *r = Eigen::Vector3d(s * (u - o.pixel.x()), s * (v - o.pixel.y()), 0.0);
  if (stereo) (*r)[2] = s * (u - k.bf * iz - o.right_u);
  if (J) {
    Eigen::Matrix<double, 3, 3> Jp;
    Jp.row(0) << k.fx * iz, 0, -k.fx * pc.x() * iz * iz;
    Jp.row(1) << 0, k.fy * iz, -k.fy * pc.y() * iz * iz;
    Eigen::Matrix<double, 3, 6> Jd;
    Jd.leftCols<3>().setIdentity();
    Jd.rightCols<3>() << 0, pc.z(), -pc.y(), -pc.z(), 0, pc.x(), pc.y(), -pc.x(), 0;
    if (stereo) {
      Jp.row(2) << k.fx * iz, 0, (-k.fx * pc.x() + k.bf) * iz * iz;
      J->noalias() = s * Jp * Jd;
    } else {
      J->topRows<2>().noalias() = s * Jp.topRows<2>() * Jd;
    }
  }
  return stereo ? 3 : 2;
}

// Cost 0.5 sum rho(|r|^2) at T, and with `H`/`g` the Gauss-Newton normal equations of the
// (reweighted) whitened residuals for a left perturbation T <- exp(delta) T. False when a point lies
// behind the camera (the step leading there is rejected, as Ceres does with a failed evaluation).
bool evaluate(const SE3& T, const std::vector<ActiveObservation>& active, const PinholeIntrinsics& k, double* cost,
              Matrix6d* H, Vector6d* g) {
  double c = 0;
  if (H) {
    H->setZero();
    g->setZero();
  }
  Eigen::Vector3d r;
  Eigen::Matrix<double, 3, 6> J;
  for (const ActiveObservation& a : active) {
    const Eigen::Vector3d pc = T * a.o->point;
    if (pc.z() <= 1e-9) return false;
    const int n = whitened_residual(pc, *a.o, k, &r, H ? &J : nullptr);
    const double e2 = r.squaredNorm();
    double w = 1.0;
    c += a.huber_b > 0 ? huber(e2, a.huber_b, &w) : e2;
    if (!H) continue;
    if (n == 3) {
      H->noalias() += w * J.transpose() * J;
      g->noalias() += w * J.transpose() * r;
    } else {
      H->noalias() += w * J.topRows<2>().transpose() * J.topRows<2>();
      g->noalias() += w * J.topRows<2>().transpose() * r.head<2>();
    }
  }
  *cost = 0.5 * c;
  return true;
}

// Levenberg-Marquardt on the 6 pose parameters with Ceres's trust-region schedule (initial radius
// 1e4, damping diag(H) / radius, radius scaled by max(1/3, 1 - (2 rho - 1)^3) on success and
// shrunk by a doubling factor on failure) and its function tolerance (1e-6 relative). Returns false
// when the starting pose cannot be evaluated.
bool solve_levenberg_marquardt(SE3& T, const std::vector<ActiveObservation>& active, const PinholeIntrinsics& k,
                               int iterations) {
  double cost = 0;
  Matrix6d H;
  Vector6d g;
  if (!evaluate(T, active, k, &cost, &H, &g)) return false;
  double radius = 1e4, decrease = 2.0;
  Matrix6d H_new;
  Vector6d g_new;
  for (int it = 0; it < iterations; ++it) {
    if (g.lpNorm<Eigen::Infinity>() <= 1e-10) break;  // Ceres's gradient tolerance
    Matrix6d A = H;
    for (int i = 0; i < 6; ++i) A(i, i) += std::clamp(H(i, i), 1e-6, 1e32) / radius;
    const Vector6d dx = A.ldlt().solve(-g);
    if (!dx.allFinite()) break;
    const double model_decrease = -(g.dot(dx) + 0.5 * dx.dot(H * dx));
    const SE3 T_new = SE3::exp(dx) * T;
    double cost_new = 0;
    const bool valid = evaluate(T_new, active, k, &cost_new, &H_new, &g_new);
    const double rho = valid && model_decrease > 0 ? (cost - cost_new) / model_decrease : -1.0;
    if (rho > 1e-3) {
      const bool converged = cost - cost_new <= 1e-6 * cost || dx.norm() <= 1e-12;
      T = T_new;
      cost = cost_new;
      H = H_new;
      g = g_new;
      const double f = 2.0 * rho - 1.0;
      radius = std::min(1e16, radius / std::max(1.0 / 3.0, 1.0 - f * f * f));
      decrease = 2.0;
      if (converged) break;
    } else {
      radius /= decrease;
      decrease *= 2.0;
      if (radius < 1e-32) break;
    }
  }
  return true;
}

// The observations of one round as a single Ceres residual block over delta, the left perturbation of
// the round's starting pose T0 (2 or 3 residuals per observation). One block instead of one per
// observation spares Ceres its per-block bookkeeping, which dominated the solve of a few hundred
// 2-row blocks (BM_PoseOptimize). The Huber loss of each observation is applied here as Ceres
// applies a loss to a block: the residual and its Jacobian scaled by sqrt(rho'(s)) (Ceres's
// Corrector, since Huber's rho'' <= 0), while the cost must be 0.5 sum rho(s), which
// SummedRobustCost reports. The minimiser then takes the steps of the per-observation problem.
class PoseRoundCost : public ceres::CostFunction {
 public:
  PoseRoundCost(const PinholeIntrinsics& k, const SE3& T0, const std::vector<ActiveObservation>& active)
      : k_(k), active_(active) {
    p0_.reserve(active.size());
    int residuals = 0;
    for (const ActiveObservation& a : active) {
      p0_.push_back(T0 * a.o->point);
      residuals += a.o->right_u >= 0 ? 3 : 2;
    }
    set_num_residuals(residuals);
    mutable_parameter_block_sizes()->push_back(6);
  }

  bool Evaluate(double const* const* parameters, double* residuals, double** jacobians) const override {
    Vector6d delta;
    for (int i = 0; i < 6; ++i) delta[i] = parameters[0][i];
    const SE3 T = SE3::exp(delta);
    double* J_out = jacobians ? jacobians[0] : nullptr;  // row-major, num_residuals x 6
    Eigen::Vector3d r;
    Eigen::Matrix<double, 3, 6> J;
    double rho_sum = 0;
    for (size_t i = 0; i < active_.size(); ++i) {
      const Eigen::Vector3d pc = T * p0_[i];
      if (pc.z() <= 1e-9) return false;
      const int n = whitened_residual(pc, *active_[i].o, k_, &r, J_out ? &J : nullptr);
      const double e2 = r.squaredNorm();
      double w = 1.0;
      rho_sum += active_[i].huber_b > 0 ? huber(e2, active_[i].huber_b, &w) : e2;
      const double scale = w == 1.0 ? 1.0 : std::sqrt(w);
      for (int j = 0; j < n; ++j) residuals[j] = scale * r[j];
      residuals += n;
      if (J_out) {
        Eigen::Map<Eigen::Matrix<double, Eigen::Dynamic, 6, Eigen::RowMajor>>(J_out, n, 6) = scale * J.topRows(n);
        J_out += 6 * n;
      }
    }
    rho_sum_ = rho_sum;
    return true;
  }

  // sum rho(s) over the observations at the last evaluation.
  double rho_sum() const { return rho_sum_; }

 private:
  PinholeIntrinsics k_;
  const std::vector<ActiveObservation>& active_;
  std::vector<Eigen::Vector3d> p0_;  // the points in the camera at T0
  mutable double rho_sum_ = 0;
};

// The "loss" of a PoseRoundCost block whose observations carry their own Huber loss: Ceres takes
// the cost 0.5 rho[0] from it, here the sum of the observations' rho computed by the evaluation
// just before (Ceres evaluates a block's cost function, then its loss), and leaves the already
// corrected residuals and Jacobians as they are (rho' = 1, rho'' = 0).
class SummedRobustCost : public ceres::LossFunction {
 public:
  explicit SummedRobustCost(const PoseRoundCost& cost) : cost_(cost) {}
  void Evaluate(double /*s*/, double rho[3]) const override {
    rho[0] = cost_.rho_sum();
    rho[1] = 1.0;
    rho[2] = 0.0;
  }

 private:
  const PoseRoundCost& cost_;
};

// One round with Ceres (dense normal equations of the 6 parameters, trust region as Ceres's default).
void solve_ceres(SE3& T, const std::vector<ActiveObservation>& active, const PinholeIntrinsics& k, int iterations) {
  double delta[6] = {0, 0, 0, 0, 0, 0};
  PoseRoundCost cost(k, T, active);  // declared before the problem, so they outlive it
  SummedRobustCost loss(cost);
  const bool robust = std::any_of(active.begin(), active.end(), [](const ActiveObservation& a) { return a.huber_b > 0; });
  ceres::Problem::Options po;
  po.cost_function_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
  po.loss_function_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
  ceres::Problem problem(po);
  problem.AddResidualBlock(&cost, robust ? &loss : nullptr, delta);
  ceres::Solver::Options so;
  so.linear_solver_type = ceres::DENSE_NORMAL_CHOLESKY;
  so.max_num_iterations = iterations;
  so.logging_type = ceres::SILENT;
  so.num_threads = 1;
  ceres::Solver::Summary summary;
  ceres::Solve(so, &problem, &summary);
  Vector6d d;
  for (int i = 0; i < 6; ++i) d[i] = delta[i];
  T = SE3::exp(d) * T;
}

}  // namespace

double observation_chi2(const SE3& T_cw, const PoseObservation& o, const PinholeCamera& c, double bf) {
  const Eigen::Vector3d pc = T_cw * o.point;
  if (pc.z() <= 1e-6) return std::numeric_limits<double>::infinity();
  const double u = c.fx * pc.x() / pc.z() + c.cx;
  const double v = c.fy * pc.y() / pc.z() + c.cy;
  double e2 = (u - o.pixel.x()) * (u - o.pixel.x()) + (v - o.pixel.y()) * (v - o.pixel.y());
  if (o.right_u >= 0) {
    const double er = u - bf / pc.z() - o.right_u;
    e2 += er * er;
  }
  return e2 * o.inv_sigma * o.inv_sigma;
}

PoseEstimate optimize_pose(const SE3& initial, const std::vector<PoseObservation>& obs, const PinholeCamera& camera,
                           double bf, const PoseOptimizerOptions& options) {
  PoseEstimate est;
  est.T_cw = initial;
  est.inlier.assign(obs.size(), 1);
  est.inliers = static_cast<int>(obs.size());
  if (obs.size() < 3) return est;
  const PinholeIntrinsics K{camera.fx, camera.fy, camera.cx, camera.cy, bf};

  std::vector<ActiveObservation> active;
  active.reserve(obs.size());
  for (int round = 0; round < options.rounds; ++round) {
    const bool robust = round < options.robust_rounds;
    active.clear();
    for (size_t i = 0; i < obs.size(); ++i) {
      if (!est.inlier[i]) continue;
      const bool stereo = obs[i].right_u >= 0;
      // A point behind the camera at the round's start cannot be linearised: it sits this round out
      // (the chi2 test below then flags it).
      if ((est.T_cw * obs[i].point).z() <= 1e-9) continue;
      active.push_back({&obs[i], robust ? (stereo ? options.chi2_stereo : options.chi2_mono) : 0.0});
    }
    if (active.size() < 3) break;
    if (options.solver == PoseSolver::kCeres)
      solve_ceres(est.T_cw, active, K, options.iterations);
    else
      solve_levenberg_marquardt(est.T_cw, active, K, options.iterations);

    est.inliers = 0;
    for (size_t i = 0; i < obs.size(); ++i) {
      const double chi2 = observation_chi2(est.T_cw, obs[i], camera, bf);
      const double th = obs[i].right_u >= 0 ? options.chi2_stereo : options.chi2_mono;
      est.inlier[i] = chi2 <= th ? 1 : 0;
      est.inliers += est.inlier[i];
    }
    if (est.inliers < 10) break;
  }
  return est;
}

}  // namespace wardmap::slam
