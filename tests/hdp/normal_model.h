// Test models shared by the hdp tests.
#pragma once

#include <Eigen/Core>
#include <cmath>
#include <cstdint>
#include <random>
#include <utility>
#include <vector>

#include "hdp/crf_model.h"

namespace wardmap::hdp {

// Conjugate Normal model with known variance: x ~ N(mu_k, sigma^2 I), mu_k ~ N(mu0, tau^2 I).
class NormalModel : public CrfModel {
 public:
  NormalModel(std::vector<std::vector<Eigen::VectorXd>> data, double sigma, double tau, Eigen::VectorXd mu0)
      : data_(std::move(data)), s2_(sigma * sigma), t2_(tau * tau), mu0_(std::move(mu0)) {}

  double log_predictive(const ItemRef& x, const std::vector<ItemRef>& members) const override {
    Eigen::VectorXd sum = Eigen::VectorXd::Zero(mu0_.size());
    for (const ItemRef& m : members) sum += at(m);
    const double prec = 1 / t2_ + members.size() / s2_;
    const Eigen::VectorXd mean = (mu0_ / t2_ + sum / s2_) / prec;
    return log_normal(at(x), mean, s2_ + 1 / prec);
  }
  double log_predictive_new(const ItemRef& x) const override { return log_normal(at(x), mu0_, s2_ + t2_); }
  bool cannot_link(const ItemRef& a, const ItemRef& b) const override {
    for (const auto& [p, q] : forbidden)
      if ((a == p && b == q) || (a == q && b == p)) return true;
    return false;
  }
  std::vector<std::pair<ItemRef, ItemRef>> forbidden;

 private:
  const Eigen::VectorXd& at(const ItemRef& r) const { return data_[r.group][r.item]; }
  static double log_normal(const Eigen::VectorXd& x, const Eigen::VectorXd& mu, double var) {
    return -0.5 * x.size() * std::log(2 * M_PI * var) - 0.5 * (x - mu).squaredNorm() / var;
  }
  std::vector<std::vector<Eigen::VectorXd>> data_;
  double s2_, t2_;
  Eigen::VectorXd mu0_;
};

// Standard normal from raw engine output (Box-Muller), so the data do not depend on the library.
struct Gauss {
  std::mt19937_64 rng;
  explicit Gauss(std::uint64_t seed) : rng(seed) {}
  double u() { return (static_cast<double>(rng() >> 11) + 0.5) * 0x1.0p-53; }
  double operator()() { return std::sqrt(-2 * std::log(u())) * std::cos(2 * M_PI * u()); }
};

}  // namespace wardmap::hdp
