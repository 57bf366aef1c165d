// Marginal distributions: moments reproduce the inputs, x -> z -> x round trips in both
// tails, native and moment parameterisations agree, and the error messages name the field.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include <boost/math/constants/constants.hpp>
#include <boost/math/quadrature/gauss_kronrod.hpp>

#include "clients/reliability/distributions.h"

namespace rel = pfem::reliability;
using rel::Distribution;
using rel::DistributionKind;

namespace {

struct MomentCase {
  DistributionKind kind;
  double mean;
  double stddev;
  double lower = 0.0;
  double upper = 0.0;
};

std::vector<MomentCase> moment_cases() {
  const double inf = std::numeric_limits<double>::infinity();
  return {
      {DistributionKind::kNormal, 3.0, 0.7},
      {DistributionKind::kLognormal, 5.0, 0.5},
      {DistributionKind::kLognormal, 2.0, 2.5},
      {DistributionKind::kUniform, 1.0, 0.3},
      {DistributionKind::kGumbel, 2.0, 0.6},
      {DistributionKind::kFrechet, 5.0, 1.0},
      {DistributionKind::kFrechet, 100.0, 60.0},
      {DistributionKind::kWeibull, 10.0, 1.0},
      {DistributionKind::kWeibull, 3.0, 4.0},
      {DistributionKind::kGamma, 4.0, 1.5},
      {DistributionKind::kExponential, 3.0, 2.0},
      {DistributionKind::kBeta, 0.3, 0.1, 0.0, 1.0},
      {DistributionKind::kBeta, 12.0, 3.0, 5.0, 25.0},
      {DistributionKind::kTruncatedNormal, 1.0, 0.5, 0.0, inf},
      {DistributionKind::kTruncatedNormal, 0.4, 0.25, 0.0, 1.0},
  };
}

std::string label(const MomentCase& c) {
  return std::string(rel::to_string(c.kind)) + "(" + std::to_string(c.mean) + ", " +
         std::to_string(c.stddev) + ")";
}

// E[h(X)] = integral over z of h(x(z)) phi(z): an independent check of mean() and stddev().
template <class F>
double expectation(const Distribution& d, F h) {
  auto integrand = [&](double z) {
    return h(d.from_standard_normal(z)) * rel::standard_normal_pdf(z);
  };
  return boost::math::quadrature::gauss_kronrod<double, 61>::integrate(integrand, -35.0, 35.0, 15,
                                                                       1e-13);
}

}  // namespace

TEST(ReliabilityDistributions, MomentsReproduceTheInputs) {
  for (const auto& c : moment_cases()) {
    SCOPED_TRACE(label(c));
    const Distribution d = Distribution::from_moments(c.kind, c.mean, c.stddev, c.lower, c.upper);
    // mean() and stddev() are Boost's mean() / standard_deviation() where Boost has the family.
    EXPECT_NEAR(d.mean(), c.mean, 1e-10 * std::abs(c.mean) + 1e-12);
    EXPECT_NEAR(d.stddev(), c.stddev, 1e-9 * c.stddev);
    // And by quadrature over the quantile function.
    const double m = expectation(d, [](double x) { return x; });
    const double v = expectation(d, [&](double x) { return (x - m) * (x - m); });
    EXPECT_NEAR(m, c.mean, 1e-6 * c.stddev);
    EXPECT_NEAR(std::sqrt(v), c.stddev, 1e-4 * c.stddev);
  }
}

TEST(ReliabilityDistributions, RoundTripThroughStandardNormalInBothTails) {
  for (const auto& c : moment_cases()) {
    SCOPED_TRACE(label(c));
    const Distribution d = Distribution::from_moments(c.kind, c.mean, c.stddev, c.lower, c.upper);
    // Deep tails only where x stays resolvable there: next to a finite bound of a bounded,
    // shifted or truncated variable x keeps ~1e-16 of relative room, so stop at |z| = 5.
    const bool open_tails = c.kind == DistributionKind::kNormal ||
                            c.kind == DistributionKind::kLognormal ||
                            c.kind == DistributionKind::kGumbel ||
                            c.kind == DistributionKind::kFrechet ||
                            c.kind == DistributionKind::kWeibull ||
                            c.kind == DistributionKind::kGamma;
    for (double z : {-8.0, -5.0, -2.5, -1.0, 0.0, 0.3, 1.0, 2.5, 5.0, 8.0}) {
      if (!open_tails && std::abs(z) > 5.0) continue;
      const double x = d.from_standard_normal(z);
      ASSERT_TRUE(std::isfinite(x));
      EXPECT_NEAR(d.to_standard_normal(x), z, 1e-7 * std::max(1.0, std::abs(z))) << "z = " << z;
      EXPECT_NEAR(d.cdf(x) + d.ccdf(x), 1.0, 1e-14);
    }
    // x -> z -> x at the mean and a spread of points inside the support.
    for (double p : {1e-6, 0.01, 0.3, 0.5, 0.8, 0.999, 1 - 1e-7}) {
      const double x = d.quantile(p);
      EXPECT_NEAR(d.from_standard_normal(d.to_standard_normal(x)), x,
                  1e-9 * std::max(std::abs(x), c.stddev));
      EXPECT_NEAR(d.cdf(x), p, 1e-12 + 1e-9 * p);
    }
  }
}

TEST(ReliabilityDistributions, PdfIsTheDerivativeOfTheCdf) {
  for (const auto& c : moment_cases()) {
    SCOPED_TRACE(label(c));
    const Distribution d = Distribution::from_moments(c.kind, c.mean, c.stddev, c.lower, c.upper);
    for (double p : {0.05, 0.3, 0.5, 0.9}) {
      const double x = d.quantile(p);
      const double h = 1e-5 * c.stddev;
      const double fd = (d.cdf(x + h) - d.cdf(x - h)) / (2 * h);
      EXPECT_NEAR(d.pdf(x), fd, 1e-6 * std::abs(fd) + 1e-12);
    }
  }
}

TEST(ReliabilityDistributions, NativeParametersMatchTheClosedForms) {
  const double pi = boost::math::constants::pi<double>();
  const double euler = boost::math::constants::euler<double>();
  // Lognormal: lambda = ln(mean) - zeta^2/2, zeta^2 = ln(1 + cov^2).
  const Distribution ln = Distribution::from_moments(DistributionKind::kLognormal, 5.0, 0.5);
  const double zeta = std::sqrt(std::log1p(0.01));
  EXPECT_NEAR(ln.parameters()[0].second, std::log(5.0) - 0.5 * zeta * zeta, 1e-14);
  EXPECT_NEAR(ln.parameters()[1].second, zeta, 1e-14);
  // Gumbel: scale = sigma sqrt(6) / pi, location = mean - gamma scale.
  const Distribution gu = Distribution::from_moments(DistributionKind::kGumbel, 2.0, 0.6);
  EXPECT_NEAR(gu.parameters()[1].second, 0.6 * std::sqrt(6.0) / pi, 1e-14);
  EXPECT_NEAR(gu.parameters()[0].second, 2.0 - euler * 0.6 * std::sqrt(6.0) / pi, 1e-14);
  EXPECT_NEAR(gu.cdf(1.0), std::exp(-std::exp(-(1.0 - gu.parameters()[0].second) /
                                              gu.parameters()[1].second)), 1e-15);
  // Weibull with shape 2: cov = sqrt(4/pi - 1) exactly (Rayleigh).
  const double cov2 = std::sqrt(4.0 / pi - 1.0);
  const Distribution wb = Distribution::from_moments(DistributionKind::kWeibull, 1.0, cov2);
  EXPECT_NEAR(wb.parameters()[1].second, 2.0, 1e-10);
  EXPECT_NEAR(wb.parameters()[0].second, 2.0 / std::sqrt(pi), 1e-10);
  // Fréchet: F = exp(-(u/x)^k).
  const Distribution fr = Distribution::frechet(3.0, 4.0);
  EXPECT_NEAR(fr.cdf(5.0), std::exp(-std::pow(3.0 / 5.0, 4.0)), 1e-15);
  EXPECT_NEAR(fr.mean(), 3.0 * std::tgamma(0.75), 1e-13);
  // Exponential from mean and stddev is shifted: lower = mean - stddev.
  const Distribution ex = Distribution::from_moments(DistributionKind::kExponential, 3.0, 2.0);
  EXPECT_DOUBLE_EQ(ex.support().first, 1.0);
  EXPECT_NEAR(ex.cdf(2.0), 1.0 - std::exp(-0.5), 1e-15);
}

TEST(ReliabilityDistributions, ErrorsNameTheField) {
  auto message = [](auto f) {
    try {
      f();
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_EQ(message([] { Distribution::from_moments(DistributionKind::kNormal, 1.0, 0.0); }),
            "stddev: must be > 0");
  EXPECT_EQ(message([] { Distribution::from_moments(DistributionKind::kLognormal, -1.0, 1.0); }),
            "mean: must be > 0 for a lognormal variable");
  EXPECT_EQ(message([] { Distribution::from_moments(DistributionKind::kWeibull, 1.0, 1e-5); }),
            "stddev: no weibull distribution has this coefficient of variation");
  EXPECT_EQ(message([] { Distribution::from_moments(DistributionKind::kFrechet, -2.0, 1.0); }),
            "mean: must be > 0 for a frechet variable");
  EXPECT_EQ(message([] { Distribution::from_moments(DistributionKind::kBeta, 0.5, 0.6, 0.0, 1.0); }),
            "stddev: too large for a beta variable with this mean and these bounds");
  EXPECT_EQ(message([] { Distribution::uniform(2.0, 1.0); }), "upper: must be > lower");
  EXPECT_EQ(message([] { Distribution::weibull(1.0, -2.0); }), "shape: must be > 0");
}

TEST(ReliabilityDistributions, NamesRoundTrip) {
  for (const char* name : {"normal", "lognormal", "uniform", "gumbel", "frechet", "weibull",
                           "gamma", "exponential", "beta", "truncated_normal"}) {
    const auto kind = rel::parse_distribution_kind(name);
    ASSERT_TRUE(kind.has_value()) << name;
    EXPECT_EQ(rel::to_string(*kind), name);
  }
  EXPECT_FALSE(rel::parse_distribution_kind("Normal").has_value());
}
