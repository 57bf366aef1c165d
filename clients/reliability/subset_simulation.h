#pragma once
// Subset simulation (Au & Beck 2001, "Estimation of small failure probabilities in high
// dimensions by subset simulation", Probabilistic Engineering Mechanics 16(4)): pf as a product
// of conditional probabilities p0 of nested failure domains G(u) <= b_1 > b_2 > ... > 0, each
// level populated by the modified Metropolis algorithm (component-wise proposals accepted by the
// standard normal density ratio, then the candidate accepted if it stays in the current domain).
//
//   level 0   N samples u ~ N(0, I)                         (sample k: RandomStream(seed, k))
//   level i   b_i = the p0 N-th smallest G (mid-way to the next); the p0 N samples below seed
//             as many chains of 1 / p0 states each          (chain c: RandomStream(seed, i << 32 | c))
//   stop      when b_i <= 0: pf = p0^(i-1) * #{G < 0} / N
//
// The chains advance in lock step; at every step the p0 N candidates are evaluated
// `concurrency` at a time, so the result for a seed is the same at every concurrency. The
// c.o.v. is Au & Beck's estimate (their eqs. 27-29: level terms (1 - p_i) / (p_i N) (1 + gamma_i),
// gamma_i from the correlation of the indicator along the chains), summed over the levels as if
// they were independent.
#include <cstdint>
#include <string>
#include <vector>

#include "clients/reliability/errors.h"
#include "clients/reliability/limit_state.h"
#include "clients/reliability/nataf.h"

namespace pfem::reliability {

struct SubsetOptions {
  std::int64_t samples_per_level = 1000;  // N; p0 N and 1 / p0 must be whole numbers
  double p0 = 0.1;                        // conditional probability of a level, in (0, 0.5]
  int max_levels = 20;                    // levels after the first (Monte Carlo) one
  double proposal_stddev = 1.0;           // of the component-wise normal proposals
  std::uint64_t seed = 1;
  int concurrency = 1;                    // evaluations of g at once
  std::vector<FieldError> validate() const;
};

struct SubsetLevel {
  double threshold = 0.0;         // b_i (0 for the last level)
  double probability = 0.0;       // conditional probability of the level
  double acceptance = 0.0;        // fraction of chain moves accepted (0 for level 0)
  double gamma = 0.0;             // correlation factor of the level's estimate
};

struct SubsetResult {
  bool converged = false;         // reached b <= 0 within max_levels
  std::string message;
  double pf = 0.0;
  double cov = 0.0;
  double beta = 0.0;              // -Phi^-1(pf)
  std::vector<SubsetLevel> levels;
  std::int64_t evaluations = 0;
};

// Throws ProblemError for invalid options and whatever g throws.
SubsetResult subset_simulation(const LimitState& g, const NatafTransform& transform,
                               const SubsetOptions& options = {});

}  // namespace pfem::reliability
