#include "hdp/gaussian_mixture.h"

#include <gtest/gtest.h>

#include <Eigen/LU>
#include <cmath>
#include <limits>

namespace wardmap::hdp {
namespace {

double normal_pdf(double x, double mu, double s) {
  return std::exp(-0.5 * (x - mu) * (x - mu) / (s * s)) / (std::sqrt(2 * M_PI) * s);
}

TEST(GaussianMixture, SingleComponentIsTheNormalDensity) {
  GaussianMixtureOptions o;
  o.sigma_per_dim = Eigen::Vector3d(0.5, 1.0, 2.0);
  const Eigen::VectorXd mu = Eigen::Vector3d(1, -2, 3);
  const GaussianMixture g = GaussianMixture::from_measurements({mu}, o);
  const Eigen::VectorXd x = Eigen::Vector3d(1.3, -1.0, 0.5);
  const double expected = normal_pdf(1.3, 1, 0.5) * normal_pdf(-1.0, -2, 1.0) * normal_pdf(0.5, 3, 2.0);
  EXPECT_NEAR(g.density(x), expected, 1e-12 * expected + 1e-15);
  EXPECT_NEAR(g.log_density(x), std::log(expected), 1e-12);
}

TEST(GaussianMixture, MixtureIsTheWeightedSumOfComponents) {
  GaussianMixtureOptions o;
  o.sigma = 0.7;
  const std::vector<Eigen::VectorXd> means = {Eigen::Vector2d(0, 0), Eigen::Vector2d(1, 2), Eigen::Vector2d(-1, 1)};
  const GaussianMixture equal = GaussianMixture::from_measurements(means, o);
  const GaussianMixture weighted = GaussianMixture::from_measurements(means, o, {1.0, 2.0, 5.0});
  const Eigen::VectorXd x = Eigen::Vector2d(0.3, 0.9);
  auto comp = [&](const Eigen::VectorXd& m) { return normal_pdf(x(0), m(0), 0.7) * normal_pdf(x(1), m(1), 0.7); };
  EXPECT_NEAR(equal.density(x), (comp(means[0]) + comp(means[1]) + comp(means[2])) / 3, 1e-12);
  EXPECT_NEAR(weighted.density(x), (1 * comp(means[0]) + 2 * comp(means[1]) + 5 * comp(means[2])) / 8, 1e-12);
  EXPECT_NEAR(weighted.weight(2), 5.0 / 8, 1e-15);
}

TEST(GaussianMixture, FullCovarianceMatchesClosedForm) {
  Eigen::Matrix2d S;
  S << 2.0, 0.6, 0.6, 0.5;
  const GaussianMixture g =
      GaussianMixture::from_measurements({Eigen::Vector2d(1, 1)}, std::vector<Eigen::MatrixXd>{S});
  const Eigen::Vector2d d = Eigen::Vector2d(0.2, 1.7) - Eigen::Vector2d(1, 1);
  const double expected = std::exp(-0.5 * d.dot(S.inverse() * d)) / (2 * M_PI * std::sqrt(S.determinant()));
  EXPECT_NEAR(g.density(Eigen::Vector2d(0.2, 1.7)), expected, 1e-12);
}

TEST(GaussianMixture, IntegratesToOneOnAGrid) {
  GaussianMixtureOptions o;
  o.sigma = 0.5;
  const GaussianMixture g = GaussianMixture::from_measurements({Eigen::Vector2d(0, 0), Eigen::Vector2d(1, -1)}, o);
  double sum = 0;
  const double h = 0.05;
  for (double x = -5; x < 6; x += h)
    for (double y = -6; y < 5; y += h) sum += g.density(Eigen::Vector2d(x, y)) * h * h;
  EXPECT_NEAR(sum, 1.0, 1e-3);
}

TEST(GaussianMixture, PaperEq3NormaliserDiffersByAConstant) {
  GaussianMixtureOptions o;
  const std::vector<Eigen::VectorXd> m = {Eigen::VectorXd::Zero(6), Eigen::VectorXd::Constant(6, 0.1)};
  const GaussianMixture proper = GaussianMixture::from_measurements(m, o);
  o.paper_eq3_normalizer = true;
  const GaussianMixture paper = GaussianMixture::from_measurements(m, o);
  const Eigen::VectorXd x = Eigen::VectorXd::Constant(6, 0.05);
  EXPECT_NEAR(paper.log_density(x) - proper.log_density(x), 2.5 * std::log(2 * M_PI), 1e-12);
}

TEST(GaussianMixture, FarPointsStayFiniteInLogSpace) {
  const GaussianMixture g = GaussianMixture::from_measurements({Eigen::Vector2d(0, 0)});
  const double l = g.log_density(Eigen::Vector2d(1000, 0));  // 10^4 sigma away: density underflows
  EXPECT_TRUE(std::isfinite(l));
  EXPECT_EQ(g.density(Eigen::Vector2d(1000, 0)), 0.0);
}

TEST(GaussianMixture, MaxDensityOverPointsPicksTheBestExplained) {
  const GaussianMixture g = GaussianMixture::from_measurements({Eigen::Vector2d(0, 0), Eigen::Vector2d(5, 5)});
  int arg = -1;
  const std::vector<Eigen::VectorXd> pts = {Eigen::Vector2d(2, 2), Eigen::Vector2d(5.01, 4.98),
                                            Eigen::Vector2d(0.2, 0)};
  const double best = g.max_log_density(pts, &arg);
  EXPECT_EQ(arg, 1);
  EXPECT_DOUBLE_EQ(best, g.log_density(pts[1]));
  EXPECT_DOUBLE_EQ(g.max_density(pts), std::exp(best));
  EXPECT_EQ(g.max_log_density({}, &arg), -std::numeric_limits<double>::infinity());
  EXPECT_EQ(arg, -1);
}

TEST(GaussianMixture, RejectsBadInput) {
  GaussianMixtureOptions o;
  o.sigma_per_dim = Eigen::Vector2d(1, 1);
  ASSERT_TRUE(o.validate(3).has_value());
  EXPECT_NE(o.validate(3)->find("sigma_per_dim"), std::string::npos);
  o = GaussianMixtureOptions{};
  o.sigma = 0;
  EXPECT_NE(o.validate(2)->find("sigma"), std::string::npos);
  GaussianMixture g;
  g.add_component(1, Eigen::Vector2d(0, 0), Eigen::Matrix2d::Identity());
  EXPECT_THROW(g.add_component(1, Eigen::Vector3d(0, 0, 0), Eigen::Matrix3d::Identity()), std::invalid_argument);
  EXPECT_THROW(g.add_component(1, Eigen::Vector2d(0, 0), -Eigen::Matrix2d::Identity()), std::invalid_argument);
  EXPECT_THROW(g.add_component(-1, Eigen::Vector2d(0, 0), Eigen::Matrix2d::Identity()), std::invalid_argument);
}

}  // namespace
}  // namespace wardmap::hdp
