// Gaussian mixture over D-dimensional vectors (Assoc. Eq. 2-3): the pose model of one group object.
// Each measurement associated with the object becomes one component, mean = the measurement,
//   Gamma(O | Theta) = sum_z lambda_z phi(O | mu_z, Sigma_z)                      // Assoc. Eq. 2
//   phi(O | mu, Sigma) = exp(-(O - mu)^T Sigma^-1 (O - mu) / 2) / normaliser      // Assoc. Eq. 3
// The features (e.g. position + rotation vector for a 6-DoF pose) are chosen by the caller; this
// class only sees vectors and treats them as Euclidean (no angle wrapping).
#pragma once

#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <optional>
#include <string>
#include <vector>

namespace wardmap::hdp {

struct GaussianMixtureOptions {
  // Component covariance: diag(sigma_per_dim^2) when sigma_per_dim is set, else sigma^2 I. The paper
  // gives no value; 0.1 suits metres when the features are positions.
  double sigma = 0.1;
  Eigen::VectorXd sigma_per_dim;
  // Assoc. Eq. 3 prints the normaliser sqrt(2 pi) |Sigma|^(1/2); a D-dimensional Gaussian needs
  // (2 pi)^(D/2) |Sigma|^(1/2). false = the proper density (default), true = Eq. 3 as printed
  // (the same density times (2 pi)^((D-1)/2); rankings are unaffected, absolute values are not).
  bool paper_eq3_normalizer = false;
  // Empty when valid (for vectors of dimension dim; dim < 0 skips the dimension checks), else a
  // sentence naming the offending field.
  std::optional<std::string> validate(int dim = -1) const;
  // The covariance these options describe for dimension dim.
  Eigen::MatrixXd covariance(int dim) const;
};

class GaussianMixture {
 public:
  explicit GaussianMixture(bool paper_eq3_normalizer = false) : paper_eq3_normalizer_(paper_eq3_normalizer) {}

  // Assoc. Eq. 2: one component per measurement with the options' covariance; equal weights when
  // weights is empty, else the given (non-negative, not all zero) weights, normalised.
  static GaussianMixture from_measurements(const std::vector<Eigen::VectorXd>& measurements,
                                           const GaussianMixtureOptions& options = {},
                                           const std::vector<double>& weights = {});
  // The same with one (full, symmetric positive-definite) covariance per measurement.
  static GaussianMixture from_measurements(const std::vector<Eigen::VectorXd>& measurements,
                                           const std::vector<Eigen::MatrixXd>& covariances,
                                           const std::vector<double>& weights = {}, bool paper_eq3_normalizer = false);

  // Adds a component with an unnormalised weight (weights are normalised when evaluating).
  // Throws std::invalid_argument on a dimension mismatch, a negative weight or a covariance that is
  // not positive definite.
  void add_component(double weight, const Eigen::VectorXd& mean, const Eigen::MatrixXd& covariance);

  int dim() const { return dim_; }
  int size() const { return static_cast<int>(components_.size()); }
  bool empty() const { return components_.empty(); }
  const Eigen::VectorXd& mean(int z) const { return components_[z].mean; }
  double weight(int z) const { return components_[z].weight / total_weight_; }

  // log Gamma(x) (log-sum-exp over the components); -inf for an empty mixture.
  double log_density(const Eigen::VectorXd& x) const;
  double density(const Eigen::VectorXd& x) const;
  // log phi(x | Theta_z), Assoc. Eq. 3.
  double component_log_density(int z, const Eigen::VectorXd& x) const;
  // max_i log Gamma(points[i]) and which point attains it (-inf / -1 when points is empty). The
  // prior of Assoc. III-A.2: the best-explained measurement of another group object.
  double max_log_density(const std::vector<Eigen::VectorXd>& points, int* argmax = nullptr) const;
  double max_density(const std::vector<Eigen::VectorXd>& points, int* argmax = nullptr) const;

 private:
  struct Component {
    double weight;
    Eigen::VectorXd mean;
    Eigen::MatrixXd chol_l;  // Sigma = L L^T
    double log_norm;         // log of 1 / normaliser
  };
  bool paper_eq3_normalizer_;
  int dim_ = -1;
  double total_weight_ = 0;
  std::vector<Component> components_;
};

}  // namespace wardmap::hdp
