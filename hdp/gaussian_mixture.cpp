#include "hdp/gaussian_mixture.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>

namespace wardmap::hdp {
namespace {

constexpr double kLog2Pi = 1.8378770664093454836;  // log(2 pi)

}  // namespace

std::optional<std::string> GaussianMixtureOptions::validate(int dim) const {
  std::ostringstream err;
  if (dim == 0 || dim < -1)
    err << "dimension must be >= 1 (got " << dim << ")";
  else if (sigma_per_dim.size() == 0 && !(sigma > 0 && std::isfinite(sigma)))
    err << "sigma must be positive and finite (got " << sigma << ")";
  else if (dim > 0 && sigma_per_dim.size() != 0 && sigma_per_dim.size() != dim)
    err << "sigma_per_dim has " << sigma_per_dim.size() << " entries, the vectors have " << dim;
  else if (sigma_per_dim.size() != 0 && !(sigma_per_dim.allFinite() && (sigma_per_dim.array() > 0).all()))
    err << "sigma_per_dim entries must be positive and finite";
  if (err.tellp() == 0) return std::nullopt;
  return err.str();
}

Eigen::MatrixXd GaussianMixtureOptions::covariance(int dim) const {
  if (sigma_per_dim.size() == dim) return sigma_per_dim.array().square().matrix().asDiagonal();
  return Eigen::MatrixXd::Identity(dim, dim) * sigma * sigma;
}

GaussianMixture GaussianMixture::from_measurements(const std::vector<Eigen::VectorXd>& measurements,
                                                   const GaussianMixtureOptions& options,
                                                   const std::vector<double>& weights) {
  GaussianMixture gmm(options.paper_eq3_normalizer);
  if (measurements.empty()) return gmm;
  const int dim = static_cast<int>(measurements.front().size());
  if (auto err = options.validate(dim)) throw std::invalid_argument("GaussianMixtureOptions: " + *err);
  const Eigen::MatrixXd cov = options.covariance(dim);
  return from_measurements(measurements, std::vector<Eigen::MatrixXd>(measurements.size(), cov), weights,
                           options.paper_eq3_normalizer);
}

GaussianMixture GaussianMixture::from_measurements(const std::vector<Eigen::VectorXd>& measurements,
                                                   const std::vector<Eigen::MatrixXd>& covariances,
                                                   const std::vector<double>& weights, bool paper_eq3_normalizer) {
  if (covariances.size() != measurements.size())
    throw std::invalid_argument("GaussianMixture: one covariance per measurement expected");
  if (!weights.empty() && weights.size() != measurements.size())
    throw std::invalid_argument("GaussianMixture: one weight per measurement expected (or none)");
  GaussianMixture gmm(paper_eq3_normalizer);
  for (size_t i = 0; i < measurements.size(); ++i)
    gmm.add_component(weights.empty() ? 1.0 : weights[i], measurements[i], covariances[i]);
  if (!gmm.empty() && !(gmm.total_weight_ > 0)) throw std::invalid_argument("GaussianMixture: weights are all zero");
  return gmm;
}

void GaussianMixture::add_component(double weight, const Eigen::VectorXd& mean, const Eigen::MatrixXd& covariance) {
  const int d = static_cast<int>(mean.size());
  if (d < 1) throw std::invalid_argument("GaussianMixture: empty mean");
  if (dim_ >= 0 && d != dim_)
    throw std::invalid_argument("GaussianMixture: mean has dimension " + std::to_string(d) + ", mixture has " +
                                std::to_string(dim_));
  if (!(weight >= 0) || !std::isfinite(weight)) throw std::invalid_argument("GaussianMixture: weight must be >= 0");
  if (covariance.rows() != d || covariance.cols() != d)
    throw std::invalid_argument("GaussianMixture: covariance must be " + std::to_string(d) + "x" + std::to_string(d));
  if (!mean.allFinite()) throw std::invalid_argument("GaussianMixture: mean is not finite");
  Eigen::LLT<Eigen::MatrixXd> llt(0.5 * (covariance + covariance.transpose()));
  if (llt.info() != Eigen::Success) throw std::invalid_argument("GaussianMixture: covariance is not positive definite");
  Component c;
  c.weight = weight;
  c.mean = mean;
  c.chol_l = llt.matrixL();
  const double log_det = 2.0 * c.chol_l.diagonal().array().log().sum();
  const double dims_in_normaliser = paper_eq3_normalizer_ ? 1.0 : static_cast<double>(d);
  c.log_norm = -0.5 * dims_in_normaliser * kLog2Pi - 0.5 * log_det;
  dim_ = d;
  total_weight_ += weight;
  components_.push_back(std::move(c));
}

double GaussianMixture::component_log_density(int z, const Eigen::VectorXd& x) const {
  const Component& c = components_.at(z);
  if (x.size() != dim_) throw std::invalid_argument("GaussianMixture: point has the wrong dimension");
  const Eigen::VectorXd y = c.chol_l.triangularView<Eigen::Lower>().solve(x - c.mean);
  return c.log_norm - 0.5 * y.squaredNorm();
}

double GaussianMixture::log_density(const Eigen::VectorXd& x) const {
  const double neg_inf = -std::numeric_limits<double>::infinity();
  if (components_.empty() || !(total_weight_ > 0)) return neg_inf;
  std::vector<double> terms;
  terms.reserve(components_.size());
  double hi = neg_inf;
  for (int z = 0; z < size(); ++z) {
    if (components_[z].weight <= 0) continue;
    terms.push_back(std::log(components_[z].weight) + component_log_density(z, x));
    hi = std::max(hi, terms.back());
  }
  if (!std::isfinite(hi)) return hi;
  double sum = 0;
  for (double t : terms) sum += std::exp(t - hi);
  return hi + std::log(sum) - std::log(total_weight_);
}

double GaussianMixture::density(const Eigen::VectorXd& x) const { return std::exp(log_density(x)); }

double GaussianMixture::max_log_density(const std::vector<Eigen::VectorXd>& points, int* argmax) const {
  double best = -std::numeric_limits<double>::infinity();
  int arg = -1;
  for (int i = 0; i < static_cast<int>(points.size()); ++i) {
    const double l = log_density(points[i]);
    if (arg < 0 || l > best) {
      best = l;
      arg = i;
    }
  }
  if (argmax) *argmax = arg;
  return best;
}

double GaussianMixture::max_density(const std::vector<Eigen::VectorXd>& points, int* argmax) const {
  return std::exp(max_log_density(points, argmax));
}

}  // namespace wardmap::hdp
