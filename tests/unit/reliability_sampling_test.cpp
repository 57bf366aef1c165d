// Crude Monte Carlo and importance sampling against an exact pf, and their determinism.
#include <gtest/gtest.h>

#include <cmath>

#include "clients/reliability/form.h"
#include "clients/reliability/sampling.h"

namespace rel = pfem::reliability;

namespace {

// g = 2 - (u1 + u2) / sqrt(2) in standard normals: exactly pf = Phi(-2) = 0.0227501...
struct Linear {
  std::vector<std::string> names{"a", "b"};
  rel::NatafTransform transform{{rel::Distribution::normal(0.0, 1.0), rel::Distribution::normal(0.0, 1.0)}};
  rel::ExpressionLimitState g{"2 - (a + b) / sqrt(2)", names};
};

}  // namespace

TEST(ReliabilitySampling, MonteCarloMatchesTheExactProbability) {
  const Linear p;
  const double exact = rel::standard_normal_cdf(-2.0);
  const rel::SamplingResult r = rel::monte_carlo(p.g, p.transform, {200000, 42});
  EXPECT_EQ(r.samples, 200000);
  EXPECT_EQ(r.evaluations, 200000);
  EXPECT_NEAR(r.cov, std::sqrt((1 - exact) / (200000 * exact)), 0.05 * r.cov);
  EXPECT_NEAR(r.pf, exact, 3 * r.cov * exact);
  EXPECT_NEAR(r.beta, -rel::standard_normal_quantile(r.pf), 1e-12);
}

TEST(ReliabilitySampling, ImportanceSamplingAtTheDesignPoint) {
  const Linear p;
  const double exact = rel::standard_normal_cdf(-2.0);
  const rel::FormResult f = rel::run_form(p.g, p.transform);
  const rel::SamplingResult r = rel::importance_sampling(p.g, p.transform, f.u, {20000, 42});
  EXPECT_NEAR(r.pf, exact, 3 * r.cov * exact);
  EXPECT_LT(r.cov, 0.02);  // far better than Monte Carlo's 0.047 with as many samples
}

TEST(ReliabilitySampling, SameSeedSameResultOtherSeedOtherSamples) {
  const Linear p;
  const auto a = rel::monte_carlo(p.g, p.transform, {5000, 9});
  const auto b = rel::monte_carlo(p.g, p.transform, {5000, 9});
  const auto c = rel::monte_carlo(p.g, p.transform, {5000, 10});
  EXPECT_EQ(a.failures, b.failures);
  EXPECT_EQ(a.pf, b.pf);
  EXPECT_NE(a.failures, c.failures);
}

// Samples draw from streams keyed by their index: the same sums at every concurrency.
TEST(ReliabilitySampling, SameResultAtEveryConcurrency) {
  const Linear p;
  const rel::FormResult f = rel::run_form(p.g, p.transform);
  for (int c : {2, 3, 8}) {
    const auto a = rel::importance_sampling(p.g, p.transform, f.u, {3000, 5, 1});
    const auto b = rel::importance_sampling(p.g, p.transform, f.u, {3000, 5, c});
    EXPECT_EQ(a.pf, b.pf);
    EXPECT_EQ(a.cov, b.cov);
    const auto m = rel::monte_carlo(p.g, p.transform, {3000, 5, 1});
    const auto n = rel::monte_carlo(p.g, p.transform, {3000, 5, c});
    EXPECT_EQ(m.failures, n.failures);
  }
}

TEST(ReliabilitySampling, InvalidSampleCountIsAnError) {
  const Linear p;
  try {
    rel::monte_carlo(p.g, p.transform, {0, 1});
    FAIL() << "expected an error";
  } catch (const rel::ProblemError& e) {
    EXPECT_EQ(std::string(e.what()), "samples: must be > 0");
  }
}
