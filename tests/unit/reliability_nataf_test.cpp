// The Nataf transformation: fictive correlations against closed forms, the transform's round
// trip and Jacobian, and the errors for unreachable or non-positive-definite correlations.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "clients/reliability/nataf.h"

namespace rel = pfem::reliability;
using rel::Distribution;
using rel::DistributionKind;

TEST(ReliabilityNataf, GaussHermiteRuleIntegratesPolynomialsExactly) {
  const auto rule = rel::gauss_hermite_rule(20);
  double m0 = 0, m2 = 0, m4 = 0, m6 = 0;
  for (std::size_t k = 0; k < rule.nodes.size(); ++k) {
    const double z = rule.nodes[k];
    m0 += rule.weights[k];
    m2 += rule.weights[k] * z * z;
    m4 += rule.weights[k] * std::pow(z, 4);
    m6 += rule.weights[k] * std::pow(z, 6);
  }
  EXPECT_NEAR(m0, 1.0, 1e-13);
  EXPECT_NEAR(m2, 1.0, 1e-12);
  EXPECT_NEAR(m4, 3.0, 1e-11);
  EXPECT_NEAR(m6, 15.0, 1e-10);
}

TEST(ReliabilityNataf, NormalPairKeepsItsCorrelationExactly) {
  const Distribution a = Distribution::normal(10.0, 2.0);
  const Distribution b = Distribution::normal(-3.0, 0.5);
  for (double rho : {-0.9, -0.3, 0.2, 0.75}) {
    EXPECT_EQ(rel::fictive_correlation(a, b, rho), rho);
    // The quadrature itself reproduces it too (it is exact for a bilinear integrand).
    EXPECT_NEAR(rel::nataf_correlation(a, b, rho), rho, 1e-13);
  }
}

TEST(ReliabilityNataf, LognormalPairMatchesTheClosedForm) {
  // rho0 = ln(1 + rho d1 d2) / sqrt(ln(1 + d1^2) ln(1 + d2^2)), d = coefficients of variation
  // (e.g. Der Kiureghian & Liu 1986; exact for two lognormals).
  struct Case {
    double d1, d2, rho;
  };
  for (const Case c : {Case{0.1, 0.2, 0.5}, Case{0.3, 0.5, -0.4}, Case{0.5, 0.8, 0.7},
                       Case{1.0, 0.4, 0.3}}) {
    const Distribution a = Distribution::from_moments(DistributionKind::kLognormal, 5.0, 5.0 * c.d1);
    const Distribution b = Distribution::from_moments(DistributionKind::kLognormal, 2.0, 2.0 * c.d2);
    const double exact = std::log1p(c.rho * c.d1 * c.d2) /
                         std::sqrt(std::log1p(c.d1 * c.d1) * std::log1p(c.d2 * c.d2));
    EXPECT_NEAR(rel::fictive_correlation(a, b, c.rho), exact, 1e-8)
        << "d1 " << c.d1 << " d2 " << c.d2 << " rho " << c.rho;
  }
}

TEST(ReliabilityNataf, NormalLognormalMatchesTheClosedForm) {
  // rho0 = rho d / sqrt(ln(1 + d^2)) for a normal and a lognormal of c.o.v. d.
  const Distribution a = Distribution::normal(0.0, 1.0);
  const Distribution b = Distribution::from_moments(DistributionKind::kLognormal, 3.0, 1.5);
  const double d = 0.5;
  EXPECT_NEAR(rel::fictive_correlation(a, b, 0.6), 0.6 * d / std::sqrt(std::log1p(d * d)), 1e-9);
}

TEST(ReliabilityNataf, UnreachableCorrelationIsAnError) {
  // Two strongly skewed lognormals cannot be strongly negatively correlated.
  const Distribution a = Distribution::from_moments(DistributionKind::kLognormal, 1.0, 2.0);
  const Distribution b = Distribution::from_moments(DistributionKind::kLognormal, 1.0, 2.0);
  try {
    rel::fictive_correlation(a, b, -0.9);
    FAIL() << "expected an error";
  } catch (const rel::NatafError& e) {
    EXPECT_NE(std::string(e.what()).find("can only reach correlations in"), std::string::npos)
        << e.what();
  }
}

TEST(ReliabilityNataf, NonPositiveDefiniteMatrixIsAnError) {
  std::vector<Distribution> m(3, Distribution::normal(0.0, 1.0));
  Eigen::MatrixXd r(3, 3);
  r << 1.0, 0.9, -0.9, 0.9, 1.0, 0.9, -0.9, 0.9, 1.0;
  try {
    rel::NatafTransform t(m, r);
    FAIL() << "expected an error";
  } catch (const rel::NatafError& e) {
    EXPECT_EQ(std::string(e.what()), "the correlation matrix is not positive definite");
    EXPECT_EQ(e.i(), -1);
  }
}

TEST(ReliabilityNataf, TransformRoundTripAndJacobian) {
  std::vector<Distribution> m = {
      Distribution::from_moments(DistributionKind::kLognormal, 5.0, 0.5),
      Distribution::from_moments(DistributionKind::kGumbel, 2.0, 0.6),
      Distribution::uniform(0.0, 1.0),
      Distribution::from_moments(DistributionKind::kWeibull, 10.0, 2.0)};
  Eigen::MatrixXd r = Eigen::MatrixXd::Identity(4, 4);
  r(0, 1) = r(1, 0) = 0.3;
  r(1, 3) = r(3, 1) = -0.4;
  r(2, 3) = r(3, 2) = 0.5;
  const rel::NatafTransform t(m, r);
  Eigen::VectorXd u(4);
  u << 0.3, -1.2, 0.8, 2.1;
  Eigen::MatrixXd jac;
  const Eigen::VectorXd x = t.to_x(u, jac);
  EXPECT_LT((t.to_u(x) - u).norm(), 1e-10);
  for (int j = 0; j < 4; ++j) {
    const double h = 1e-6;
    Eigen::VectorXd up = u, um = u;
    up(j) += h;
    um(j) -= h;
    const Eigen::VectorXd fd = (t.to_x(up) - t.to_x(um)) / (2 * h);
    EXPECT_LT((fd - jac.col(j)).norm(), 1e-6 * (1.0 + jac.col(j).norm())) << "column " << j;
  }
  // The correlation of the transformed pair reproduces rho (by the same quadrature).
  EXPECT_NEAR(rel::nataf_correlation(m[1], m[3], t.fictive_correlation()(1, 3)), -0.4, 1e-10);
}
