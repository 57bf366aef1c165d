#include "clients/reliability/analysis.h"

#include <chrono>
#include <cmath>

namespace pfem::reliability {

std::vector<FieldError> AnalysisOptions::validate() const {
  std::vector<FieldError> errors;
  for (auto e : form.validate()) errors.push_back({"form." + e.path, e.message});
  for (auto e : sorm_options.validate()) errors.push_back({"sorm_options." + e.path, e.message});
  if (importance_sampling < 0) errors.push_back({"importance_sampling", "must be >= 0"});
  if (monte_carlo < 0) errors.push_back({"monte_carlo", "must be >= 0"});
  if (subset_simulation < 0) {
    errors.push_back({"subset_simulation", "must be >= 0"});
  } else if (subset_simulation > 0) {
    SubsetOptions subset;
    subset.samples_per_level = subset_simulation;
    for (auto e : subset.validate()) errors.push_back({"subset_simulation", e.message});
  }
  if (concurrency < 1) errors.push_back({"concurrency", "must be >= 1"});
  return errors;
}

AnalysisOptions analysis_options(const Problem& problem) {
  AnalysisOptions options;
  options.form.method = problem.method;
  const auto& o = problem.message.options();
  if (o.has_max_iterations()) options.form.max_iterations = o.max_iterations();
  if (o.has_tolerance()) options.form.tolerance = o.tolerance();
  if (o.has_sorm()) options.sorm = o.sorm();
  if (o.has_importance_sampling()) options.importance_sampling = o.importance_sampling();
  if (o.has_monte_carlo()) options.monte_carlo = o.monte_carlo();
  if (o.has_subset_simulation()) options.subset_simulation = o.subset_simulation();
  if (o.has_seed()) options.seed = o.seed();
  return options;
}

AnalysisResult analyze(const Problem& problem, const LimitState& g, const AnalysisOptions& options) {
  if (auto errors = options.validate(); !errors.empty()) throw ProblemError(std::move(errors));
  const auto start = std::chrono::steady_clock::now();
  const NatafTransform& transform = *problem.transform;
  AnalysisResult r;
  r.form = run_form(g, transform, options.form);
  const bool design_point = std::isfinite(r.form.beta);  // what the rest builds on
  if (options.sensitivities && design_point) r.sensitivities = beta_sensitivities(transform, r.form);
  if (options.sorm && design_point) {
    SormOptions sorm = options.sorm_options;
    sorm.concurrency = options.concurrency;
    r.sorm = run_sorm(g, transform, r.form, sorm);
  }
  if (options.importance_sampling > 0) {
    r.importance_sampling = importance_sampling(
        g, transform, r.form.u, {options.importance_sampling, options.seed, options.concurrency});
  }
  if (options.monte_carlo > 0) {
    r.monte_carlo =
        monte_carlo(g, transform, {options.monte_carlo, options.seed, options.concurrency});
  }
  if (options.subset_simulation > 0) {
    SubsetOptions subset;
    subset.samples_per_level = options.subset_simulation;
    subset.seed = options.seed;
    subset.concurrency = options.concurrency;
    r.subset_simulation = subset_simulation(g, transform, subset);
  }
  r.simulations = g.simulation_stats();
  r.wall_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return r;
}

}  // namespace pfem::reliability
