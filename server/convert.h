#pragma once
// Conversions between the engine's types (engine/analysis/run.h) and the wire (pfem.v1),
// shared by the server, pfemctl and the tests. Header-only engine types: linking the engine
// is not needed for these.
#include <string>
#include <vector>

#include "engine/analysis/run.h"
#include "engine/io/model_io.h"
#include "pfem/v1/service.pb.h"

namespace pfem::server {

pfem::v1::Histories to_proto(const Histories& histories);
Histories from_proto(const pfem::v1::Histories& histories);
pfem::v1::Summary to_proto(const RunSummary& summary);
RunSummary from_proto(const pfem::v1::Summary& summary);
pfem::v1::Result to_proto(const RunResult& result);
RunResult from_proto(const pfem::v1::Result& result);
pfem::v1::Progress to_proto(const Progress& progress);

SensitivityMethod from_proto(pfem::v1::SensitivityMethod method, SensitivityMethod fallback);
pfem::v1::SensitivityMethod to_proto(SensitivityMethod method);

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
