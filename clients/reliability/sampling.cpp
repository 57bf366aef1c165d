#include "clients/reliability/sampling.h"

#include <cmath>
#include <limits>
#include <random>

namespace pfem::reliability {

namespace {

// Standard normal variates by the Box-Muller transform over std::mt19937_64, so that a seed
// gives the same numbers with every standard library (std::normal_distribution does not).
class NormalSampler {
 public:
  explicit NormalSampler(std::uint64_t seed) : engine_(seed) {}
  double operator()() {
    if (has_spare_) {
      has_spare_ = false;
      return spare_;
    }
    constexpr double scale = 1.0 / 18446744073709551616.0;  // 2^-64
    double u1;
    do {
      u1 = static_cast<double>(engine_()) * scale;
    } while (u1 <= 0.0);
    const double u2 = static_cast<double>(engine_()) * scale;
    const double r = std::sqrt(-2.0 * std::log(u1));
    const double t = 2.0 * 3.14159265358979323846 * u2;
    spare_ = r * std::sin(t);
    has_spare_ = true;
    return r * std::cos(t);
  }

 private:
  std::mt19937_64 engine_;
  double spare_ = 0.0;
  bool has_spare_ = false;
};

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

void check(const SamplingOptions& options) {
  if (auto errors = options.validate(); !errors.empty()) throw ProblemError(std::move(errors));
}

}  // namespace

std::vector<FieldError> SamplingOptions::validate() const {
  std::vector<FieldError> errors;
  if (samples <= 0) errors.push_back({"samples", "must be > 0"});
  return errors;
}

SamplingResult monte_carlo(const LimitState& g, const NatafTransform& transform,
                           const SamplingOptions& options) {
  check(options);
  StandardSpaceFunction G(g, transform);
  NormalSampler normal(options.seed);
  Eigen::VectorXd u(transform.size());
  std::int64_t failures = 0;
  for (std::int64_t k = 0; k < options.samples; ++k) {
    for (int i = 0; i < u.size(); ++i) u(i) = normal();
    if (G.value(u) < 0) ++failures;
  }
  const double f = static_cast<double>(failures);
  SamplingResult r = finish(options.samples, failures, f, f);
  r.evaluations = G.evaluations();
  return r;
}

SamplingResult importance_sampling(const LimitState& g, const NatafTransform& transform,
                                   const Eigen::VectorXd& design_u, const SamplingOptions& options) {
  check(options);
  StandardSpaceFunction G(g, transform);
  NormalSampler normal(options.seed);
  const int n = transform.size();
  Eigen::VectorXd v(n);
  std::int64_t failures = 0;
  double sum = 0.0;
  double sum_sq = 0.0;
  const double half_beta2 = 0.5 * design_u.squaredNorm();
  for (std::int64_t k = 0; k < options.samples; ++k) {
    for (int i = 0; i < n; ++i) v(i) = normal();
    const Eigen::VectorXd u = design_u + v;
    if (G.value(u) < 0) {
      ++failures;
      // phi(u) / phi(u - u*) = exp(-u*.v - ||u*||^2 / 2)
      const double w = std::exp(-design_u.dot(v) - half_beta2);
      sum += w;
      sum_sq += w * w;
    }
  }
  SamplingResult r = finish(options.samples, failures, sum, sum_sq);
  r.evaluations = G.evaluations();
  return r;
}

}  // namespace pfem::reliability
