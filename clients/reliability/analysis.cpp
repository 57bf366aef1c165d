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
  if (options.sorm && design_point) r.sorm = run_sorm(g, transform, r.form, options.sorm_options);
  if (options.importance_sampling > 0) {
    r.importance_sampling =
        importance_sampling(g, transform, r.form.u, {options.importance_sampling, options.seed});
  }
  if (options.monte_carlo > 0) {
    r.monte_carlo = monte_carlo(g, transform, {options.monte_carlo, options.seed});
  }
  r.simulations = g.simulation_stats();
  r.wall_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return r;
}

}  // namespace pfem::reliability
