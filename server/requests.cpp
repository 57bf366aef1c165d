#include "server/requests.h"

#include <cmath>

#include "engine/analysis/functional.h"
#include "engine/analysis/run_estimate.h"
#include "engine/io/model_builder.h"
#include "engine/io/model_io.h"
#include "engine/io/model_warnings.h"
#include "server/convert.h"
#include "server/model_cost.h"
#include "server/status.h"

namespace pfem::server {

pfem::v1::Model check_run_request(
    pfem::v1::Model model,
    const google::protobuf::RepeatedPtrField<pfem::v1::ParameterValue>& values,
    const pfem::v1::RunOptions& options, const Limits& limits,
    const std::string& options_prefix, std::vector<FieldError> more_errors,
    std::shared_ptr<const PreparedRun>* prepared) {
  check_model_cost(model, limits);  // before validation, which grows with these counts
  auto errors = apply_parameter_values(model, values);
  for (auto& e : validate_model(model)) errors.push_back(std::move(e));
  for (auto& e : polygon_errors(model)) errors.push_back(std::move(e));
  for (auto& e : validate_run_options(model, options, options_prefix)) {
    errors.push_back(std::move(e));
  }
  for (auto& e : more_errors) errors.push_back(std::move(e));
  if (!errors.empty()) throw_invalid(errors);
  check_run_limits(model,
                   options.has_t_end() ? std::optional<double>(options.t_end()) : std::nullopt,
                   options.has_dt() ? std::optional<double>(options.dt()) : std::nullopt, limits);
  // What only building the model finds (within the limits, so the build is affordable).
  try {
    if (prepared) {
      *prepared = prepare_run(model, to_run_options(options, SensitivityMethod::kDdm), /*validated=*/true);
    } else {
      build_validated_problem(model);
    }
  } catch (const ModelError& e) {
    throw_invalid(e.errors());
  }
  return model;
}

namespace {

FunctionalKind kind_of(pfem::v1::Functional::Kind kind) {
  switch (kind) {
    case pfem::v1::Functional::KIND_VALUE_AT: return FunctionalKind::kValueAt;
    case pfem::v1::Functional::KIND_MAX: return FunctionalKind::kMax;
    case pfem::v1::Functional::KIND_MIN: return FunctionalKind::kMin;
    case pfem::v1::Functional::KIND_MAX_ABS: return FunctionalKind::kMaxAbs;
    default: return FunctionalKind::kFinal;
  }
}

}  // namespace

FunctionalSpec functional_spec(const pfem::v1::Functional& f) {
  FunctionalSpec spec{f.recorder(), kind_of(f.kind()), f.time()};
  if (f.has_window_start()) spec.window_start = f.window_start();
  if (f.has_window_end()) spec.window_end = f.window_end();
  return spec;
}

std::vector<FieldError> check_functionals(
    const pfem::v1::Model& model,
    const google::protobuf::RepeatedPtrField<pfem::v1::Functional>& functionals) {
  std::vector<FieldError> errors;
  if (functionals.empty()) errors.push_back({"functionals", "at least one is required"});
  for (int i = 0; i < functionals.size(); ++i) {
    const auto& f = functionals[i];
    const std::string path = "functionals[" + std::to_string(i) + "]";
    bool known = false;
    for (const auto& r : model.recorders()) known |= r.name() == f.recorder();
    if (!known) {
      errors.push_back({path + ".recorder", "no recorder '" + f.recorder() + "' in the model"});
    }
    if (f.kind() == pfem::v1::Functional::KIND_UNSPECIFIED ||
        !pfem::v1::Functional::Kind_IsValid(f.kind())) {
      errors.push_back({path + ".kind", "must be VALUE_AT, MAX, MIN, MAX_ABS or FINAL"});
    } else if (auto bad = check_functional_window(functional_spec(f))) {
      errors.push_back({path + "." + bad->first, bad->second});
    }
    if (f.kind() == pfem::v1::Functional::KIND_VALUE_AT && !std::isfinite(f.time())) {
      errors.push_back({path + ".time", "must be finite"});
    }
  }
  return errors;
}

void check_submit_request(const pfem::v1::SubmitJobRequest& request, const Limits& limits) {
  if (request.has_timeout_seconds() &&
      !(request.timeout_seconds() > 0.0 && std::isfinite(request.timeout_seconds()))) {
    throw_invalid({{"timeout_seconds", "must be > 0 and finite"}});
  }
  check_run_request(request.model(), request.parameter_values(), request.options(), limits);
}

EvaluateRun check_evaluate_request(const pfem::v1::EvaluateRequest& request,
                                   pfem::v1::Model model, const Limits& limits) {
  EvaluateRun run;
  auto& options = run.options;
  if (request.has_t_end()) options.set_t_end(request.t_end());
  if (request.has_dt()) options.set_dt(request.dt());
  if (request.has_fdm_eps()) options.set_fdm_eps(request.fdm_eps());
  options.set_sensitivity(request.sensitivity() == pfem::v1::SENSITIVITY_METHOD_UNSPECIFIED
                              ? pfem::v1::SENSITIVITY_METHOD_DDM
                              : request.sensitivity());
  *options.mutable_params() = request.params();
  auto functional_errors = check_functionals(model, request.functionals());
  run.model = check_run_request(std::move(model), request.parameter_values(), options, limits,
                                "", std::move(functional_errors), &run.prepared);
  return run;
}

pfem::v1::ValidateModelResponse check_validate_request(const pfem::v1::Model& model,
                                                       const Limits& limits) {
  // Only a model within the cost limits is validated, and only one within the particle
  // limit too is built (which finds more).
  check_model_cost(model, limits);
  auto errors = polygon_errors(model);
  const bool buildable = errors.empty() && estimate_particles(model) <= limits.max_particles;
  for (auto& e : buildable ? model_errors(model) : validate_model(model)) {
    errors.push_back(std::move(e));
  }
  pfem::v1::ValidateModelResponse response;
  for (const auto& e : errors) {
    auto* fe = response.add_errors();
    fe->set_path(e.path);
    fe->set_message(e.message);
  }
  response.set_valid(response.errors().empty());
  if (response.valid()) {
    for (const auto& w : model_warnings(model)) {
      auto* fw = response.add_warnings();
      fw->set_path(w.path);
      fw->set_message(w.message);
    }
  }
  const RunEstimate estimate = estimate_run(model);
  response.set_estimated_particles(estimate.particles);
  response.set_steps(estimate.steps);
  response.set_estimated_elements(estimate.elements);
  response.set_estimated_seconds(estimate.seconds);
  response.set_seconds_per_particle_step(estimate.seconds_per_particle_step);
  try {
    check_run_limits(model, std::nullopt, std::nullopt, limits);
  } catch (const ServiceError& e) {
    response.set_over_limit(e.what());  // SubmitJob would answer RESOURCE_EXHAUSTED
  }
  return response;
}

}  // namespace pfem::server
