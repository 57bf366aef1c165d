#pragma once
// One reliability analysis of a built problem: FORM, the sensitivities of beta to the
// moments, and on request SORM, importance sampling at the design point, crude Monte Carlo and
// subset simulation; their independent evaluations of g run `concurrency` at a time.
#include <cstdint>
#include <optional>
#include <vector>

#include "clients/reliability/errors.h"
#include "clients/reliability/form.h"
#include "clients/reliability/limit_state.h"
#include "clients/reliability/problem_io.h"
#include "clients/reliability/sampling.h"
#include "clients/reliability/sensitivity.h"
#include "clients/reliability/sorm.h"
#include "clients/reliability/subset_simulation.h"

namespace pfem::reliability {

struct AnalysisOptions {
  FormOptions form;
  bool sensitivities = true;               // d beta / d (mean, stddev) of every variable
  bool sorm = false;
  SormOptions sorm_options;
  std::int64_t importance_sampling = 0;    // samples; 0: none
  std::int64_t monte_carlo = 0;            // samples; 0: none
  std::int64_t subset_simulation = 0;      // samples per level; 0: none
  std::uint64_t seed = 1;                  // of the sampling methods
  int concurrency = 1;                     // evaluations of g at once (sampling, SORM)

  // Every invalid setting, with paths such as "form.max_iterations" or "monte_carlo".
  std::vector<FieldError> validate() const;
};

// The problem file's method and "options" block, on top of the defaults.
AnalysisOptions analysis_options(const Problem& problem);

struct AnalysisResult {
  FormResult form;
  std::vector<MomentSensitivity> sensitivities;  // empty unless asked
  std::optional<SormResult> sorm;
  std::optional<SamplingResult> importance_sampling;
  std::optional<SamplingResult> monte_carlo;
  std::optional<SubsetResult> subset_simulation;
  std::optional<SimulationStats> simulations;    // model limit states: the PFEM runs behind g
  double wall_seconds = 0.0;
};

// Throws ProblemError for invalid options and whatever the limit state throws.
AnalysisResult analyze(const Problem& problem, const LimitState& g, const AnalysisOptions& options);

}  // namespace pfem::reliability
