#pragma once
// Checks shared by the handlers that start runs (SubmitJob, Evaluate): every field error at
// once (INVALID_ARGUMENT), then the resource limits (RESOURCE_EXHAUSTED).
#include <memory>
#include <string>
#include <vector>

#include "engine/analysis/functional.h"
#include "engine/analysis/run.h"
#include "engine/io/model_io.h"
#include "pfem/v1/service.pb.h"
#include "server/limits.h"

namespace pfem::server {

// The model with the parameter values applied, after checking (in this order, all errors
// of the first three together): the parameter values, the model (validate_model, paths as
// in `pfem validate`), the run options (paths "<options_prefix>.t_end", ...) and
// more_errors (found by the caller), then the limits, then what only building the model finds
// (the model is validated once). With prepared, the build is the run's (pfem::prepare_run
// with the options as to_run_options(options, DDM) gives them), kept in *prepared.
// Throws ServiceError.
pfem::v1::Model check_run_request(
    pfem::v1::Model model,
    const google::protobuf::RepeatedPtrField<pfem::v1::ParameterValue>& values,
    const pfem::v1::RunOptions& options, const Limits& limits,
    const std::string& options_prefix = "options", std::vector<FieldError> more_errors = {},
    std::shared_ptr<const PreparedRun>* prepared = nullptr);

// SubmitJob's checks: timeout_seconds, then check_run_request. Throws ServiceError.
void check_submit_request(const pfem::v1::SubmitJobRequest& request, const Limits& limits);

// What Evaluate runs, once its request has passed the checks.
struct EvaluateRun {
  pfem::v1::Model model;        // the parameter values applied
  pfem::v1::RunOptions options;
  std::shared_ptr<const PreparedRun> prepared;  // the model built for the run (options.prepared)
};

// Evaluate's checks on `model` (the request's own, or the one stored under model_id): the
// functionals, then check_run_request with the request's run options (paths without a
// prefix: "t_end"). Throws ServiceError.
EvaluateRun check_evaluate_request(const pfem::v1::EvaluateRequest& request,
                                   pfem::v1::Model model, const Limits& limits);

// ValidateModel's answer: every field error of a model within the cost limits (and what only
// building finds, when it is within the particle limit too), the warnings of a valid one, the
// run estimate, and the limit a SubmitJob would exceed. Throws ServiceError(RESOURCE_EXHAUSTED) beyond the cost limits.
pfem::v1::ValidateModelResponse check_validate_request(const pfem::v1::Model& model,
                                                       const Limits& limits);

// The engine's spec of a request functional (kind, time and window as given).
FunctionalSpec functional_spec(const pfem::v1::Functional& f);

// Every problem with Evaluate's functionals against the model's recorders
// ("functionals[1].recorder: no recorder 'x' in the model").
std::vector<FieldError> check_functionals(
    const pfem::v1::Model& model,
    const google::protobuf::RepeatedPtrField<pfem::v1::Functional>& functionals);

}  // namespace pfem::server
