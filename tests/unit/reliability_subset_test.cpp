// Subset simulation against published failure probabilities of linear limit states
// (pf = Phi(-beta): 2.326e-4 at beta = 3.5, 1.017e-6 at beta = 4.75, the benchmark values used
// by Au & Beck 2001 and later comparisons), its c.o.v. estimate against the scatter of
// independent runs, and its independence of the concurrency.
#include <gtest/gtest.h>

#include <cmath>
#include <numeric>

#include "clients/reliability/subset_simulation.h"

namespace rel = pfem::reliability;

namespace {

// g = beta - (a + b + c) / sqrt(3) in standard normals: exactly pf = Phi(-beta).
struct Linear {
  explicit Linear(double beta)
      : g{std::to_string(beta) + " - (a + b + c) / sqrt(3)", names} {}
  std::vector<std::string> names{"a", "b", "c"};
  rel::NatafTransform transform{{rel::Distribution::normal(0.0, 1.0),
                                 rel::Distribution::normal(0.0, 1.0),
                                 rel::Distribution::normal(0.0, 1.0)}};
  rel::ExpressionLimitState g;
};

rel::SubsetOptions options(std::int64_t n, std::uint64_t seed, int concurrency = 1) {
  rel::SubsetOptions o;
  o.samples_per_level = n;
  o.seed = seed;
  o.concurrency = concurrency;
  return o;
}

}  // namespace

TEST(ReliabilitySubset, LinearBeta35WithinItsCov) {
  const Linear p(3.5);
  const double exact = rel::standard_normal_cdf(-3.5);
  ASSERT_NEAR(exact, 2.33e-4, 0.005e-4);
  const rel::SubsetResult r = rel::subset_simulation(p.g, p.transform, options(2000, 1));
  ASSERT_TRUE(r.converged) << r.message;
  EXPECT_EQ(r.levels.size(), 4u);  // 0.1^3 > 2.3e-4 > 0.1^4: three intermediate levels
  EXPECT_GT(r.cov, 0.1);
  EXPECT_LT(r.cov, 0.4);
  EXPECT_NEAR(r.pf, exact, 3 * r.cov * exact);
  EXPECT_NEAR(r.beta, -rel::standard_normal_quantile(r.pf), 1e-12);
  // N at level 0, then (1 - p0) N new states per level at most (a rejected component-wise
  // proposal that moves nothing costs no evaluation).
  EXPECT_GT(r.evaluations, 2000 + 3 * 1000);
  EXPECT_LE(r.evaluations, 2000 + 3 * 1800);
}

TEST(ReliabilitySubset, LinearBeta475WithinItsCov) {
  const Linear p(4.75);
  const double exact = rel::standard_normal_cdf(-4.75);
  const rel::SubsetResult r = rel::subset_simulation(p.g, p.transform, options(2000, 3));
  ASSERT_TRUE(r.converged) << r.message;
  EXPECT_GE(r.levels.size(), 6u);  // 1.017e-6 is a hair above 0.1^6: 6 or 7 levels
  EXPECT_LE(r.levels.size(), 7u);
  EXPECT_NEAR(r.pf, exact, 3 * r.cov * exact);
}

// 40 independent runs: their mean agrees with Phi(-3.5) within its standard error, and the
// scatter of the runs agrees with the c.o.v. each run reports (Au & Beck's estimate; it
// ignores the correlation between levels, so it may be somewhat low, not by a factor 2).
TEST(ReliabilitySubset, ReportedCovMatchesTheScatterOfRuns) {
  const Linear p(3.5);
  const double exact = rel::standard_normal_cdf(-3.5);
  const int runs = 40;
  std::vector<double> pf;
  double reported = 0.0;
  for (int s = 0; s < runs; ++s) {
    const auto r = rel::subset_simulation(p.g, p.transform, options(1000, 100 + s));
    pf.push_back(r.pf);
    reported += r.cov / runs;
  }
  const double mean = std::accumulate(pf.begin(), pf.end(), 0.0) / runs;
  double var = 0.0;
  for (double x : pf) var += (x - mean) * (x - mean) / (runs - 1);
  const double scatter = std::sqrt(var) / mean;
  EXPECT_NEAR(mean, exact, 3 * std::sqrt(var / runs));
  EXPECT_GT(scatter, 0.5 * reported);
  EXPECT_LT(scatter, 2.0 * reported);
}

TEST(ReliabilitySubset, SameResultAtEveryConcurrency) {
  const Linear p(3.5);
  const auto a = rel::subset_simulation(p.g, p.transform, options(500, 9, 1));
  const auto b = rel::subset_simulation(p.g, p.transform, options(500, 9, 4));
  const auto c = rel::subset_simulation(p.g, p.transform, options(500, 10, 1));
  EXPECT_EQ(a.pf, b.pf);
  EXPECT_EQ(a.cov, b.cov);
  EXPECT_EQ(a.evaluations, b.evaluations);
  ASSERT_EQ(a.levels.size(), b.levels.size());
  for (std::size_t i = 0; i < a.levels.size(); ++i) {
    EXPECT_EQ(a.levels[i].threshold, b.levels[i].threshold);
  }
  EXPECT_NE(a.pf, c.pf);
}

TEST(ReliabilitySubset, InvalidOptionsNameTheField) {
  const Linear p(3.5);
  rel::SubsetOptions o = options(1005, 1);
  o.proposal_stddev = 0;
  try {
    rel::subset_simulation(p.g, p.transform, o);
    FAIL() << "expected an error";
  } catch (const rel::ProblemError& e) {
    EXPECT_EQ(std::string(e.what()),
              "samples_per_level: p0 * samples_per_level and 1 / p0 must be whole numbers\n"
              "proposal_stddev: must be > 0");
  }
}
