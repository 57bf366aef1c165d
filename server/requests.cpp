#include "server/requests.h"

#include <cmath>

#include "engine/io/model_builder.h"
#include "engine/io/model_io.h"
#include "server/convert.h"
#include "server/model_cost.h"
#include "server/status.h"

namespace pfem::server {

pfem::v1::Model check_run_request(
    pfem::v1::Model model,
    const google::protobuf::RepeatedPtrField<pfem::v1::ParameterValue>& values,
    const pfem::v1::RunOptions& options, const Limits& limits,
    const std::string& options_prefix, std::vector<FieldError> more_errors) {
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
  if (auto build = model_errors(model); !build.empty()) throw_invalid(build);
  return model;
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
    }
    if (f.kind() == pfem::v1::Functional::KIND_VALUE_AT && !std::isfinite(f.time())) {
      errors.push_back({path + ".time", "must be finite"});
    }
  }
  return errors;
}

}  // namespace pfem::server
