#include "engine/analysis/run.h"

#include <chrono>
#include <cmath>
#include <optional>
#include <set>

#include "engine/analysis/blas_threads.h"
#include "engine/analysis/simulation.h"
#include "engine/io/model_builder.h"
#include "engine/io/model_io.h"
#include "engine/io/model_size.h"

namespace pfem {

namespace {

// Options checked like model fields, with the flag's name as the path.
void check_options(const RunOptions& o, const Problem& pb, std::vector<const ParameterSpec*>& chosen) {
  std::vector<FieldError> errors;
  if (o.t_end && !(std::isfinite(*o.t_end) && *o.t_end > 0)) errors.push_back({"t_end", "must be > 0"});
  if (o.dt && !(std::isfinite(*o.dt) && *o.dt > 0)) errors.push_back({"dt", "must be > 0"});
  if (o.vtk_every && *o.vtk_every < 1) errors.push_back({"vtk_every", "must be >= 1"});
  if (o.threads < 1 || o.threads > kMaxThreads)
    errors.push_back({"threads", "must be in [1, " + std::to_string(kMaxThreads) + "]"});
  if (!(std::isfinite(o.fdm_eps) && o.fdm_eps > 0 && o.fdm_eps < 0.1))
    errors.push_back({"fdm_eps", "must be in (0, 0.1)"});
  if (o.checkpoint_every < 0) errors.push_back({"checkpoint_every", "must be >= 0"});
  if (o.checkpoint_every > 0 && o.checkpoint_file.empty())
    errors.push_back({"checkpoint_file", "is needed with checkpoint_every"});
  if (o.sensitivity == SensitivityMethod::kFdm && (o.checkpoint_every > 0 || !o.restart_from.empty()))
    errors.push_back({o.checkpoint_every > 0 ? "checkpoint_every" : "restart_from",
                      "checkpoints are for runs without sensitivities or with the DDM (an FDM run is 2P + 1 runs)"});
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

// The problem of the model with one parameter set to value: rebuilt from the model, so that
// every kind of target (fluid, thickness, materials, sections, beams) takes the value.
Problem problem_with(const pfem::v1::Model& model, const Problem& base, const std::string& name, double value) {
  pfem::v1::Model changed = model;
  for (auto& p : *changed.mutable_parameters())
    if (p.name() == name) p.set_value(value);
  Problem pb = build_problem(changed);
  pb.t_end = base.t_end, pb.dt = base.dt;  // the run's overrides
  return pb;
}

// A problem_with for value, or nullopt when the model rejects that value (a parameter at a
// bound of its range, as a viscosity of 0).
std::optional<Problem> problem_if_valid(const pfem::v1::Model& model, const Problem& base, const std::string& name,
                                        double value) {
  try {
    return problem_with(model, base, name, value);
  } catch (const ModelError&) {
    return std::nullopt;
  }
}

// Central differences: 2 runs per parameter, step eps*|value| (eps when the value is 0); a
// one-sided difference against the unperturbed run where one side leaves the parameter's range.
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
  for (const auto* p : params) {
    const double step = o.fdm_eps * (p->value != 0.0 ? std::abs(p->value) : 1.0);
    const auto plus = problem_if_valid(model, base, p->name, p->value + step);
    const auto minus = problem_if_valid(model, base, p->name, p->value - step);
    if (!plus && !minus) problem_with(model, base, p->name, p->value + step);  // throws: why
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
    per_param.push_back(std::move(d));
  }
  for (std::size_t i = 0; i < sens.time.size(); ++i)
    for (std::size_t j = 0; j < nrec; ++j)
      for (std::size_t k = 0; k < params.size(); ++k) sens.rows[i].push_back(per_param[k][i][j]);
  result.summary.sensitivity_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace

const char* method_name(SensitivityMethod m) {
  return m == SensitivityMethod::kDdm ? "ddm" : m == SensitivityMethod::kFdm ? "fdm" : "none";
}

RunResult run(const pfem::v1::Model& model, const RunOptions& options) {
  keep_blas_in_calling_thread();  // bit-identical results beside other runs and in any program
  Problem problem = build_problem(model);
  std::vector<const ParameterSpec*> params;
  check_options(options, problem, params);
  if (options.t_end) problem.t_end = *options.t_end;
  if (options.dt) problem.dt = *options.dt;
  if (problem.dt > problem.t_end) throw ModelError("dt", "must not exceed t_end");
  if (const std::string why = too_many_steps(problem.t_end, problem.dt, "dt"); !why.empty())
    throw ModelError("t_end", why);

  std::optional<Problem> with_seeds;  // DDM: the problem with the parameters' seeds
  if (options.sensitivity == SensitivityMethod::kDdm) {
    std::vector<std::string> names;
    for (const auto* p : params) names.push_back(p->name);
    with_seeds = build_problem(model, names);
    with_seeds->t_end = problem.t_end, with_seeds->dt = problem.dt;
  }

  Checkpointing checkpoints{options.checkpoint_file, options.checkpoint_every, checkpointed_run(model, options)};
  std::optional<Checkpoint> restart;
  if (!options.restart_from.empty()) {
    restart = read_checkpoint(options.restart_from);
    check_same_run(restart->run, checkpoints.run);
    checkpoints.restore = &restart->state;
  }
  RunResult result;
  SimulationOutput sim = simulate(with_seeds ? *with_seeds : problem, options, &checkpoints);
  result.responses = std::move(sim.responses);
  result.sensitivities = std::move(sim.sensitivities);
  result.summary = sim.summary;
  result.summary.sensitivity_method = method_name(options.sensitivity);
  for (const auto* p : params) {
    result.summary.parameters.push_back(p->name);
    result.summary.parameter_values.push_back(p->value);
  }
  if (options.sensitivity == SensitivityMethod::kFdm && result.summary.status == RunStatus::kCompleted)
    finite_differences(model, problem, options, params, result);
  result.summary.wall_seconds = result.summary.response_seconds + result.summary.sensitivity_seconds;
  return result;
}

}  // namespace pfem
