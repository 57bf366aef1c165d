#include "server/evaluator.h"

#include <chrono>

#include "engine/analysis/functional.h"
#include "server/convert.h"
#include "server/hashing.h"
#include "server/requests.h"
#include "server/status.h"
#include "wire/convert.h"

namespace pfem::server {
void Evaluator::evaluate(const pfem::v1::EvaluateRequest& request, const StopFunction& should_stop,
                         pfem::v1::EvaluateResponse* response) const {
  const auto started = std::chrono::steady_clock::now();
  pfem::v1::Model model;
  switch (request.source_case()) {
    case pfem::v1::EvaluateRequest::kModel:
      model = request.model();
      break;
    case pfem::v1::EvaluateRequest::kModelId: {
      auto stored = store_.get_model(request.model_id());
      if (!stored) {
        throw ServiceError(grpc::StatusCode::NOT_FOUND,
                           "no model '" + request.model_id() + "' (store it with PutModel)");
      }
      model = std::move(*stored);
      break;
    }
    default:
      throw_invalid({{"model", "required (or model_id)"}});
  }
  const EvaluateRun run = check_evaluate_request(request, std::move(model), limits_);
  const pfem::v1::RunOptions& options = run.options;
  const std::string key = sha256_hex(canonical_bytes(run.model) + '\n' + canonical_bytes(options));
  const auto compute = [&] {
    RunOptions engine_options = to_run_options(options, SensitivityMethod::kDdm);
    engine_options.prepared = run.prepared;  // built once, by the checks
    return jobs_.run_now(run.model, std::move(engine_options), should_stop);
  };
  bool hit = false;
  const auto result = request.no_cache() ? std::make_shared<const RunResult>(compute())
                                         : cache_.get_or_compute(key, compute, &hit);
  const auto& summary = result->summary;
  if (summary.status == RunStatus::kCancelled) {
    throw ServiceError(grpc::StatusCode::CANCELLED, "the run was cancelled: " + summary.message);
  }
  if (summary.status == RunStatus::kFailed) {
    throw ServiceError(grpc::StatusCode::FAILED_PRECONDITION,
                       "the simulation failed at step " + std::to_string(summary.failed_step) +
                           " (t = " + std::to_string(summary.failed_time) +
                           " s): " + summary.message);
  }
  const std::vector<std::string>& params = summary.parameters;
  const bool with_gradient = options.sensitivity() != pfem::v1::SENSITIVITY_METHOD_NONE;
  const std::vector<std::string> no_params;
  for (int i = 0; i < request.functionals_size(); ++i) {
    const auto& f = request.functionals(i);
    const FunctionalSpec spec = functional_spec(f);
    FunctionalValue v;
    try {
      v = evaluate_functional(result->responses, result->sensitivities,
                              with_gradient ? params : no_params, spec);
    } catch (const FunctionalError& e) {
      throw_invalid({{"functionals[" + std::to_string(i) + "]." + e.field(), e.what()}});
    }
    auto* out = response->add_values();
    out->set_name(f.name().empty() ? f.recorder() + ":" + functional_kind_name(spec.kind)
                                   : f.name());
    out->set_value(v.value);
    out->set_time(v.time);
    out->mutable_gradient()->Assign(v.gradient.begin(), v.gradient.end());
  }
  if (with_gradient) {
    for (const auto& p : params) response->add_parameters(p);
  }
  response->mutable_parameter_values()->Assign(summary.parameter_values.begin(),
                                               summary.parameter_values.end());
  response->set_cached(hit);
  response->set_run_key(key);
  *response->mutable_summary() = wire::to_proto(summary);
  response->set_wall_seconds(
      std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count());
}

}  // namespace pfem::server
