#include "engine/analysis/run.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <optional>
#include <set>

#include "engine/analysis/blas_threads.h"
#include "engine/analysis/simulation.h"
#include "engine/base/assert.h"
#include "engine/io/model_builder.h"
#include "engine/io/model_checks.h"
#include "engine/io/model_io.h"
#include "engine/io/model_size.h"
#include "engine/io/model_warnings.h"

namespace pfem {

// The problem of one run (the DDM's seeds attached, the options' t_end and dt applied) and the
// parameters it differentiates, as indices into problem.parameters.
struct PreparedRun {
  Problem problem;
  std::vector<std::size_t> params;
};

namespace {

// The options' own problems, then the parameters they name that the model does not have.
void check_options(const RunOptions& o, const Problem& pb, std::vector<const ParameterSpec*>& chosen) {
  std::vector<FieldError> errors = o.validate();
  if (o.sensitivity != SensitivityMethod::kNone) {
    std::set<std::string> seen;
    for (const auto& name : o.params) {
      const ParameterSpec* found = nullptr;
      for (const auto& p : pb.parameters)
        if (p.name == name) found = &p;
      if (!found) errors.push_back({"params", "unknown parameter '" + name + "'"});
      else if (seen.insert(name).second) chosen.push_back(found);
    }
    if (o.params.empty())
      for (const auto& p : pb.parameters) chosen.push_back(&p);
    if (chosen.empty() && errors.empty())
      errors.push_back({"params", "the model names no parameter to differentiate"});
  }
  if (!errors.empty()) throw ModelError(std::move(errors));
}

// The parameter called name (checked to exist: an option or a validated direction names it).
const ParameterSpec& spec_of(const Problem& pb, const std::string& name) {
  const auto p = std::find_if(pb.parameters.begin(), pb.parameters.end(), [&](const auto& q) { return q.name == name; });
  PFEM_ASSERT(p != pb.parameters.end(), "a checked parameter name is in the problem");
  return *p;
}

// The names the DDM seeds: the options' parameters that the model has (once each, in their
// order; check_options reports the others), or every parameter of the model.
std::vector<std::string> ddm_names(const pfem::v1::Model& model, const RunOptions& o) {
  std::vector<std::string> names;
  if (o.sensitivity != SensitivityMethod::kDdm) return names;
  const auto known = [&](const std::string& name) {
    return std::any_of(model.parameters().begin(), model.parameters().end(),
                       [&](const auto& p) { return p.name() == name; });
  };
  for (const auto& name : o.params)
    if (known(name) && std::find(names.begin(), names.end(), name) == names.end()) names.push_back(name);
  if (o.params.empty())
    for (const auto& p : model.parameters()) names.push_back(p.name());
  return names;
}

// The FDM step of a parameter: eps |value| (eps when the value is 0); of a directional one, the
// largest s that moves none of its parameters by more than their own step (eps at weights 0).
double fdm_step(const Problem& pb, const ParameterSpec& p, double eps) {
  const auto own = [eps](double value) { return eps * (value != 0.0 ? std::abs(value) : 1.0); };
  if (p.direction.empty()) return own(p.value);
  double step = std::numeric_limits<double>::infinity();
  for (const auto& [name, weight] : p.direction)
    if (weight != 0.0) step = std::min(step, own(spec_of(pb, name).value) / std::abs(weight));
  return std::isfinite(step) ? step : eps;
}

// The problem of the validated model with parameter p moved by s (a directional one moves each of
// its parameters k to v_k + w_k s): rebuilt from the model, so that every kind of target (fluid,
// thickness, materials, sections, beams, wavemakers) takes the value. Throws ModelError when a
// value leaves its targets' range, the one thing validation could refuse in the moved model.
Problem problem_with(const pfem::v1::Model& model, const Problem& base, const ParameterSpec& p, double s) {
  std::vector<std::pair<std::string, double>> values;
  if (p.direction.empty()) values.emplace_back(p.name, p.value + s);
  for (const auto& [name, weight] : p.direction) values.emplace_back(name, spec_of(base, name).value + weight * s);
  pfem::v1::Model changed = model;
  for (auto& q : *changed.mutable_parameters())
    for (const auto& [name, value] : values)
      if (q.name() == name) q.set_value(value);
  if (auto errors = validate_parameter_values(changed); !errors.empty()) throw ModelError(std::move(errors));
  Problem pb = build_validated_problem(changed);
  pb.t_end = base.t_end, pb.dt = base.dt;  // the run's overrides
  return pb;
}

// A problem_with for s, or nullopt when the model rejects the values (a parameter at a bound of
// its range, as a viscosity of 0).
std::optional<Problem> problem_if_valid(const pfem::v1::Model& model, const Problem& base, const ParameterSpec& p,
                                        double s) {
  try {
    return problem_with(model, base, p, s);
  } catch (const ModelError&) {
    return std::nullopt;
  }
}

// For each response, how far its central difference w.r.t. param is from a slope: the largest
// |r+ - 2 r0 + r-| over time against the largest |r+ - r-| (for a smooth response the second
// difference is of order step^2, while the runs' Newton errors or a remeshing decision taken
// differently enter both alike), 0 where the column is negligible against its natural scale
// max |r| / theta_scale. A warning for each above kFdmNoise.
std::vector<double> one_sided_spreads(const Histories& plus, const Histories& base, const Histories& minus,
                                      double step, double theta_scale, const std::string& param,
                                      std::vector<std::string>& warnings) {
  std::vector<double> spreads(base.columns.size(), 0.0);
  for (std::size_t j = 0; j < base.columns.size(); ++j) {
    double max_r = 0.0, first = 0.0, second = 0.0;
    for (std::size_t i = 0; i < base.rows.size(); ++i) {
      const double a = plus.rows[i][j], r = base.rows[i][j], b = minus.rows[i][j];
      max_r = std::max(max_r, std::abs(r));
      first = std::max(first, std::abs(a - b));
      second = std::max(second, std::abs(a - 2.0 * r + b));
    }
    if (first == 0.0 || negligible_sensitivity(first / (2.0 * step), max_r, theta_scale)) continue;
    spreads[j] = second / first;
    if (spreads[j] <= kFdmNoise) continue;
    // Comparable one-sided differences differ by Newton errors; opposite ones by an event, such
    // as a remeshing decision, that one perturbed run took and the other did not, or are the
    // round-off of a response that is round-off itself.
    const bool event = spreads[j] > kFdmParted;
    char text[400];
    std::snprintf(text, sizeof text,
                  "d%s/d%s: the two one-sided differences differ by %.2g of the central one: %s",
                  base.columns[j].c_str(), param.c_str(), spreads[j],
                  event ? "the perturbed runs parted (a remeshing decision taken differently) or the response "
                          "is round-off, not the slope; a smaller fdm_eps keeps parted runs alike"
                        : "the runs' Newton errors, not the slope; a larger fdm_eps outweighs them");
    warnings.push_back(text);
  }
  return spreads;
}

// Central differences: 2 runs per parameter, step fdm_step(); a one-sided difference against
// the unperturbed run where one side leaves the parameter's range.
void finite_differences(const pfem::v1::Model& model, const Problem& base, const RunOptions& o,
                        const std::vector<const ParameterSpec*>& params, RunResult& result) {
  const auto start = std::chrono::steady_clock::now();
  RunOptions quiet;
  quiet.cancel = o.cancel;
  auto& sens = result.sensitivities;
  sens.time = result.responses.time;
  sens.rows.assign(sens.time.size(), {});
  for (const auto& rec : result.responses.columns)
    for (const auto* p : params) sens.columns.push_back("d" + rec + "/d" + p->name);
  const std::size_t nrec = result.responses.columns.size();
  std::vector<std::vector<std::vector<double>>> per_param;  // [param][row][recorder]
  std::vector<std::vector<double>> spread_per_param;        // [param][recorder]
  for (const auto* p : params) {
    const double step = fdm_step(base, *p, o.fdm_eps);
    const auto plus = problem_if_valid(model, base, *p, step);
    const auto minus = problem_if_valid(model, base, *p, -step);
    if (!plus && !minus) problem_with(model, base, *p, step);  // throws: why
    const auto side = [&](const std::optional<Problem>& pb) {  // the unperturbed run where invalid
      SimulationOutput out;
      if (pb) out = simulate(*pb, quiet);
      else out.responses = result.responses;
      return out;
    };
    const SimulationOutput a = side(plus), b = side(minus);
    const double width = (plus ? step : 0.0) + (minus ? step : 0.0);
    for (const auto* r : {&a, &b}) {
      if (r->summary.status != RunStatus::kCompleted || r->responses.rows.size() != sens.time.size()) {
        result.summary.status = r->summary.status == RunStatus::kCancelled ? RunStatus::kCancelled : RunStatus::kFailed;
        result.summary.message = "finite-difference run for " + p->name + " stopped: " + r->summary.message;
        sens.time.clear(), sens.rows.clear();
        return;
      }
    }
    std::vector<std::vector<double>> d(sens.time.size(), std::vector<double>(nrec));
    for (std::size_t i = 0; i < sens.time.size(); ++i)
      for (std::size_t j = 0; j < nrec; ++j)
        d[i][j] = (a.responses.rows[i][j] - b.responses.rows[i][j]) / width;
    spread_per_param.push_back(plus && minus ? one_sided_spreads(a.responses, result.responses, b.responses, step,
                                                                  step / o.fdm_eps, p->name, result.summary.warnings)
                                             : std::vector<double>(nrec, 0.0));
    per_param.push_back(std::move(d));
  }
  for (std::size_t i = 0; i < sens.time.size(); ++i)
    for (std::size_t j = 0; j < nrec; ++j)
      for (std::size_t k = 0; k < params.size(); ++k) sens.rows[i].push_back(per_param[k][i][j]);
  for (std::size_t j = 0; j < nrec; ++j)
    for (std::size_t k = 0; k < params.size(); ++k) result.fdm_spread.push_back(spread_per_param[k][j]);
  result.summary.sensitivity_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace

const char* method_name(SensitivityMethod m) {
  return m == SensitivityMethod::kDdm ? "ddm" : m == SensitivityMethod::kFdm ? "fdm" : "none";
}

std::shared_ptr<const PreparedRun> prepare_run(const pfem::v1::Model& model, const RunOptions& options,
                                               bool validated) {
  auto prepared = std::make_shared<PreparedRun>();
  Problem& problem = prepared->problem;
  const std::vector<std::string> seeded = ddm_names(model, options);
  problem = validated ? build_validated_problem(model, seeded) : build_problem(model, seeded);
  std::vector<const ParameterSpec*> params;
  check_options(options, problem, params);
  for (const auto* p : params) prepared->params.push_back(static_cast<std::size_t>(p - problem.parameters.data()));
  if (options.t_end) problem.t_end = *options.t_end;
  if (options.dt) problem.dt = *options.dt;
  if (problem.dt > problem.t_end) throw ModelError("dt", "must not exceed t_end");
  if (const std::string why = too_many_steps(problem.t_end, problem.dt, "dt"); !why.empty())
    throw ModelError("t_end", why);
  return prepared;
}

RunResult run(const pfem::v1::Model& model, const RunOptions& options) {
  keep_blas_in_calling_thread();  // bit-identical results beside other runs and in any program
  const std::shared_ptr<const PreparedRun> prepared = options.prepared ? options.prepared : prepare_run(model, options);
  const Problem& problem = prepared->problem;
  std::vector<const ParameterSpec*> params;
  for (const std::size_t k : prepared->params) params.push_back(&problem.parameters[k]);

  Checkpointing checkpoints{options.checkpoint_file, options.checkpoint_every, checkpointed_run(model, options)};
  std::optional<Checkpoint> restart;
  if (!options.restart_from.empty()) {
    restart = read_checkpoint(options.restart_from);
    check_same_run(restart->run, checkpoints.run);
    checkpoints.restore = &restart->state;
  }
  RunResult result;
  SimulationOutput sim = simulate(problem, options, &checkpoints);
  result.responses = std::move(sim.responses);
  result.sensitivities = std::move(sim.sensitivities);
  result.summary = sim.summary;
  if (auto ignored = ignored_bulk_modulus(model)) result.summary.warnings.push_back(ignored->to_string());
  // The incompressible formulation's DDM is the paper's approximation (solve/fractional_step.h).
  result.summary.sensitivity_method = options.sensitivity == SensitivityMethod::kDdm && problem.incompressible
                                          ? "ddm-approximate"
                                          : method_name(options.sensitivity);
  for (const auto* p : params) {
    result.summary.parameters.push_back(p->name);
    result.summary.parameter_values.push_back(p->value);
  }
  if (options.sensitivity == SensitivityMethod::kFdm) {
    if (auto w = fdm_tolerance_warning(problem.newton_tolerance, options.fdm_eps))
      result.summary.warnings.push_back(w->to_string());
    if (result.summary.status == RunStatus::kCompleted) finite_differences(model, problem, options, params, result);
  }
  result.summary.wall_seconds = result.summary.response_seconds + result.summary.sensitivity_seconds;
  return result;
}

}  // namespace pfem
