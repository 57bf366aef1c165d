#pragma once
// The service's requests -> the engine: run options, parameter values and their checks. The
// conversions of results both ways, shared with the clients, are wire/convert.h.
#include <string>
#include <vector>

#include "engine/analysis/run.h"
#include "engine/io/model_io.h"
#include "pfem/v1/service.pb.h"

namespace pfem::server {

// The engine options of a wire request (no progress, no cancel flag, one thread).
RunOptions to_run_options(const pfem::v1::RunOptions& options, SensitivityMethod fallback);

// Sets Model.parameters[].value for every entry of values. Returns the problems, with paths
// "<prefix>[i].name" (unknown or repeated parameter) and "<prefix>[i].value" (not finite).
std::vector<FieldError> apply_parameter_values(
    pfem::v1::Model& model,
    const google::protobuf::RepeatedPtrField<pfem::v1::ParameterValue>& values,
    const std::string& prefix = "parameter_values");

// Problems of run options: t_end, dt and fdm_eps positive and finite, params naming
// parameters of the model. Paths "<prefix>.t_end", "<prefix>.params[2]", ...
std::vector<FieldError> validate_run_options(const pfem::v1::Model& model,
                                             const pfem::v1::RunOptions& options,
                                             const std::string& prefix = "options");

}  // namespace pfem::server
