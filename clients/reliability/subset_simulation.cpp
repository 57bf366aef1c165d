#include "clients/reliability/subset_simulation.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>
#include <numeric>

#include "clients/reliability/parallel.h"
#include "clients/reliability/random_stream.h"

namespace pfem::reliability {

namespace {

// Au & Beck's gamma (eq. 29) of indicators laid out chain after chain (chain c, state s at
// c * length + s), `chains` chains of `length` states.
double chain_gamma(const std::vector<char>& indicator, std::int64_t chains, std::int64_t length) {
  const auto n = static_cast<double>(chains * length);
  const double p = static_cast<double>(std::count(indicator.begin(), indicator.end(), 1)) / n;
  const double r0 = p * (1.0 - p);
  if (!(r0 > 0)) return 0.0;
  double gamma = 0.0;
  for (std::int64_t tau = 1; tau < length; ++tau) {
    double sum = 0.0;
    for (std::int64_t c = 0; c < chains; ++c) {
      for (std::int64_t s = 0; s + tau < length; ++s) {
        sum += indicator[c * length + s] * indicator[c * length + s + tau];
      }
    }
    const double r = sum / (n - static_cast<double>(tau * chains)) - p * p;
    gamma += 2.0 * (1.0 - static_cast<double>(tau * chains) / n) * r / r0;
  }
  return gamma;
}

}  // namespace

std::vector<FieldError> SubsetOptions::validate() const {
  std::vector<FieldError> errors;
  if (!(p0 > 0 && p0 <= 0.5)) errors.push_back({"p0", "must be in (0, 0.5]"});
  if (samples_per_level < 2) {
    errors.push_back({"samples_per_level", "must be >= 2"});
  } else if (p0 > 0 && p0 <= 0.5) {
    const double chains = p0 * static_cast<double>(samples_per_level);
    const double length = 1.0 / p0;
    if (std::abs(chains - std::round(chains)) > 1e-9 || std::round(chains) < 1 ||
        std::abs(length - std::round(length)) > 1e-9) {
      errors.push_back({"samples_per_level", "p0 * samples_per_level and 1 / p0 must be whole numbers"});
    }
  }
  if (max_levels < 1) errors.push_back({"max_levels", "must be >= 1"});
  if (!(proposal_stddev > 0 && std::isfinite(proposal_stddev))) {
    errors.push_back({"proposal_stddev", "must be > 0"});
  }
  if (concurrency < 1) errors.push_back({"concurrency", "must be >= 1"});
  return errors;
}

SubsetResult subset_simulation(const LimitState& g, const NatafTransform& transform,
                               const SubsetOptions& options) {
  if (auto errors = options.validate(); !errors.empty()) throw ProblemError(std::move(errors));
  const int n = transform.size();
  const std::int64_t total = options.samples_per_level;
  const auto chains = static_cast<std::int64_t>(std::llround(options.p0 * static_cast<double>(total)));
  const auto length = static_cast<std::int64_t>(std::llround(1.0 / options.p0));
  const auto size = static_cast<std::size_t>(total);
  std::atomic<std::int64_t> evaluations{0};
  const auto G = [&](const Eigen::VectorXd& u) {
    ++evaluations;
    return StandardSpaceFunction(g, transform).value(u);
  };

  std::vector<Eigen::VectorXd> u(size, Eigen::VectorXd(n));
  std::vector<double> value(size);
  parallel_for(size, options.concurrency, [&](std::size_t k) {
    RandomStream stream(options.seed, k);
    for (int j = 0; j < n; ++j) u[k](j) = stream.normal();
    value[k] = G(u[k]);
  });

  SubsetResult r;
  double product = 1.0;  // of the conditional probabilities of the levels so far
  double cov2 = 0.0;
  double acceptance = 0.0;
  for (int level = 0;; ++level) {
    std::vector<std::size_t> order(size);
    std::iota(order.begin(), order.end(), std::size_t{0});
    std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
      return value[a] < value[b] || (value[a] == value[b] && a < b);
    });
    const auto nc = static_cast<std::size_t>(chains);
    const double b = 0.5 * (value[order[nc - 1]] + value[order[nc]]);
    const bool last = b <= 0 || level == options.max_levels;
    std::vector<char> indicator(size);
    for (std::size_t k = 0; k < size; ++k) indicator[k] = last ? value[k] < 0 : value[k] <= b;
    SubsetLevel L;
    L.threshold = last ? 0.0 : b;
    L.probability = last ? static_cast<double>(std::count(indicator.begin(), indicator.end(), 1)) /
                               static_cast<double>(total)
                         : options.p0;
    L.acceptance = acceptance;
    L.gamma = level == 0 ? 0.0 : chain_gamma(indicator, chains, length);  // level 0: independent
    if (L.probability > 0) {
      cov2 += (1.0 - L.probability) / (L.probability * static_cast<double>(total)) * (1.0 + L.gamma);
    }
    r.levels.push_back(L);
    if (last) {
      r.pf = product * L.probability;
      r.converged = b <= 0;
      r.message = r.converged ? "ok"
                              : "the failure domain was not reached in max_levels = " +
                                    std::to_string(options.max_levels) + " levels (pf is a bound)";
      break;
    }
    product *= L.probability;

    // The chains of the next level: chain c starts at the c-th smallest G and takes length - 1
    // modified-Metropolis steps inside G <= b; all chains advance together.
    std::vector<Eigen::VectorXd> next_u(size);
    std::vector<double> next_value(size);
    std::vector<RandomStream> streams;
    for (std::int64_t c = 0; c < chains; ++c) {
      next_u[c * length] = u[order[c]];
      next_value[c * length] = value[order[c]];
      streams.emplace_back(options.seed, (static_cast<std::uint64_t>(level + 1) << 32) | c);
    }
    std::atomic<std::int64_t> accepted{0};
    for (std::int64_t s = 1; s < length; ++s) {
      parallel_for(nc, options.concurrency, [&](std::size_t c) {
        const std::size_t from = c * length + s - 1;
        const Eigen::VectorXd& current = next_u[from];
        Eigen::VectorXd candidate = current;
        bool moved = false;
        for (int j = 0; j < n; ++j) {
          const double xi = current(j) + options.proposal_stddev * streams[c].normal();
          const double ratio = std::exp(-0.5 * (xi * xi - current(j) * current(j)));
          if (streams[c].uniform() < ratio) candidate(j) = xi, moved = true;
        }
        double gc = 0.0;
        if (moved && (gc = G(candidate)) <= b) {
          next_u[from + 1] = std::move(candidate);
          next_value[from + 1] = gc;
          ++accepted;
        } else {
          next_u[from + 1] = current;
          next_value[from + 1] = next_value[from];
        }
      });
    }
    acceptance = static_cast<double>(accepted) / static_cast<double>(chains * (length - 1));
    u = std::move(next_u);
    value = std::move(next_value);
  }
  r.cov = r.pf > 0 ? std::sqrt(cov2) : std::numeric_limits<double>::infinity();
  r.beta = r.pf > 0 && r.pf < 1 ? -standard_normal_quantile(r.pf)
                                : std::numeric_limits<double>::infinity();
  r.evaluations = evaluations;
  return r;
}

}  // namespace pfem::reliability
