#pragma once
// Sampling estimates of pf = P[g(X) < 0]:
//   crude Monte Carlo       u ~ N(0, I)
//   importance sampling     u ~ N(u*, I) around the design point, weights phi(u) / phi(u - u*)
// Both report pf, its coefficient of variation (standard error / pf) and the generalised
// beta = -Phi^-1(pf). Sample k draws its normals from RandomStream(seed, k), and the limit
// state is evaluated for batches of samples `concurrency` at a time: the result for a seed is
// the same at every concurrency.
#include <cstdint>
#include <string>
#include <vector>

#include <Eigen/Dense>

#include "clients/reliability/errors.h"
#include "clients/reliability/limit_state.h"
#include "clients/reliability/nataf.h"

namespace pfem::reliability {

struct SamplingOptions {
  std::int64_t samples = 100000;  // > 0
  std::uint64_t seed = 1;
  int concurrency = 1;            // evaluations of g at once (>= 1)
  std::vector<FieldError> validate() const;
};

struct SamplingResult {
  std::int64_t samples = 0;
  std::int64_t failures = 0;  // samples with g < 0
  double pf = 0.0;
  double cov = 0.0;           // coefficient of variation of the estimate (inf when pf = 0)
  double beta = 0.0;          // -Phi^-1(pf)
  std::int64_t evaluations = 0;
};

// Throw ProblemError for invalid options.
SamplingResult monte_carlo(const LimitState& g, const NatafTransform& transform,
                           const SamplingOptions& options = {});
SamplingResult importance_sampling(const LimitState& g, const NatafTransform& transform,
                                   const Eigen::VectorXd& design_u,
                                   const SamplingOptions& options = {});

}  // namespace pfem::reliability
