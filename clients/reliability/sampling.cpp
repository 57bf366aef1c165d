#include "clients/reliability/sampling.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "clients/reliability/parallel.h"
#include "clients/reliability/random_stream.h"

namespace pfem::reliability {

namespace {

SamplingResult finish(std::int64_t n, std::int64_t failures, double sum, double sum_sq) {
  SamplingResult r;
  r.samples = n;
  r.failures = failures;
  r.pf = sum / static_cast<double>(n);
  const double var = std::max(0.0, sum_sq / static_cast<double>(n) - r.pf * r.pf) /
                     static_cast<double>(n);
  r.cov = r.pf > 0 ? std::sqrt(var) / r.pf : std::numeric_limits<double>::infinity();
  r.beta = r.pf > 0 && r.pf < 1 ? -standard_normal_quantile(r.pf)
                                : (r.pf <= 0 ? std::numeric_limits<double>::infinity()
                                             : -std::numeric_limits<double>::infinity());
  return r;
}

// Evaluates G at center + v_k for every sample k, v_k the standard normals of stream (seed, k),
// in batches whose members run `concurrency` at a time, and sums the weights of the failures
// in sample order (the same sums at every concurrency). weight(v) is the sample's weight.
template <class Weight>
SamplingResult sample(const LimitState& g, const NatafTransform& transform,
                      const Eigen::VectorXd& center, const SamplingOptions& options, Weight weight) {
  if (auto errors = options.validate(); !errors.empty()) throw ProblemError(std::move(errors));
  const int n = transform.size();
  const std::int64_t batch = 256 * static_cast<std::int64_t>(options.concurrency);
  std::vector<double> values(static_cast<std::size_t>(std::min(batch, options.samples)));
  std::vector<Eigen::VectorXd> v(values.size(), Eigen::VectorXd(n));
  std::int64_t failures = 0;
  double sum = 0.0;
  double sum_sq = 0.0;
  std::int64_t evaluations = 0;
  for (std::int64_t first = 0; first < options.samples; first += batch) {
    const auto count = static_cast<std::size_t>(std::min(batch, options.samples - first));
    parallel_for(count, options.concurrency, [&](std::size_t i) {
      RandomStream stream(options.seed, static_cast<std::uint64_t>(first) + i);
      for (int j = 0; j < n; ++j) v[i](j) = stream.normal();
      StandardSpaceFunction G(g, transform);
      values[i] = G.value(center + v[i]);
    });
    evaluations += static_cast<std::int64_t>(count);
    for (std::size_t i = 0; i < count; ++i) {
      if (values[i] < 0) {
        ++failures;
        const double w = weight(v[i]);
        sum += w;
        sum_sq += w * w;
      }
    }
  }
  SamplingResult r = finish(options.samples, failures, sum, sum_sq);
  r.evaluations = evaluations;
  return r;
}

}  // namespace

std::vector<FieldError> SamplingOptions::validate() const {
  std::vector<FieldError> errors;
  if (samples <= 0) errors.push_back({"samples", "must be > 0"});
  if (concurrency < 1) errors.push_back({"concurrency", "must be >= 1"});
  return errors;
}

SamplingResult monte_carlo(const LimitState& g, const NatafTransform& transform,
                           const SamplingOptions& options) {
  return sample(g, transform, Eigen::VectorXd::Zero(transform.size()), options,
                [](const Eigen::VectorXd&) { return 1.0; });
}

SamplingResult importance_sampling(const LimitState& g, const NatafTransform& transform,
                                   const Eigen::VectorXd& design_u, const SamplingOptions& options) {
  const double half_beta2 = 0.5 * design_u.squaredNorm();
  // phi(u) / phi(u - u*) at u = u* + v: exp(-u*.v - ||u*||^2 / 2)
  return sample(g, transform, design_u, options, [&](const Eigen::VectorXd& v) {
    return std::exp(-design_u.dot(v) - half_beta2);
  });
}

}  // namespace pfem::reliability
