#include "server/convert.h"

#include <cmath>
#include <set>
#include <sstream>

#include "wire/convert.h"

namespace pfem::server {

RunOptions to_run_options(const pfem::v1::RunOptions& options, SensitivityMethod fallback) {
  RunOptions out;
  if (options.has_t_end()) out.t_end = options.t_end();
  if (options.has_dt()) out.dt = options.dt();
  out.sensitivity = wire::from_proto(options.sensitivity(), fallback);
  out.params.assign(options.params().begin(), options.params().end());
  if (options.has_fdm_eps()) out.fdm_eps = options.fdm_eps();
  out.threads = 1;
  return out;
}

std::vector<FieldError> apply_parameter_values(
    pfem::v1::Model& model,
    const google::protobuf::RepeatedPtrField<pfem::v1::ParameterValue>& values,
    const std::string& prefix) {
  std::vector<FieldError> errors;
  std::set<std::string> seen;
  for (int i = 0; i < values.size(); ++i) {
    const auto& v = values[i];
    const std::string path = prefix + "[" + std::to_string(i) + "]";
    if (!seen.insert(v.name()).second) {
      errors.push_back({path + ".name", "parameter '" + v.name() + "' given twice"});
      continue;
    }
    pfem::v1::Parameter* target = nullptr;
    for (auto& p : *model.mutable_parameters()) {
      if (p.name() == v.name()) target = &p;
    }
    if (!target) {
      errors.push_back({path + ".name", "no parameter '" + v.name() + "' in the model"});
      continue;
    }
    if (!std::isfinite(v.value())) {
      errors.push_back({path + ".value", "must be finite"});
      continue;
    }
    target->set_value(v.value());
  }
  return errors;
}

std::vector<FieldError> validate_run_options(const pfem::v1::Model& model,
                                             const pfem::v1::RunOptions& options,
                                             const std::string& prefix) {
  std::vector<FieldError> errors;
  const auto path = [&](const std::string& name) {
    return prefix.empty() ? name : prefix + "." + name;
  };
  const auto positive = [&](bool has, double v, const char* name) {
    if (has && !(std::isfinite(v) && v > 0.0)) errors.push_back({path(name), "must be > 0 and finite"});
  };
  positive(options.has_t_end(), options.t_end(), "t_end");
  positive(options.has_dt(), options.dt(), "dt");
  positive(options.has_fdm_eps(), options.fdm_eps(), "fdm_eps");
  if (options.has_t_end() || options.has_dt()) {  // the run's step against the run's end
    const double t_end = options.has_t_end() ? options.t_end() : model.analysis().t_end();
    const double dt = options.has_dt() ? options.dt() : model.analysis().dt();
    if (std::isfinite(t_end) && t_end > 0.0 && std::isfinite(dt) && dt > t_end) {
      std::ostringstream message;
      if (options.has_dt()) message << "must not exceed t_end (" << t_end << ")";
      else message << "must not be less than dt (" << dt << ")";
      errors.push_back({path(options.has_dt() ? "dt" : "t_end"), message.str()});
    }
  }
  for (int i = 0; i < options.params_size(); ++i) {
    bool found = false;
    for (const auto& p : model.parameters()) found |= p.name() == options.params(i);
    if (!found) {
      errors.push_back({path("params[" + std::to_string(i) + "]"),
                        "no parameter '" + options.params(i) + "' in the model"});
    }
  }
  if (!pfem::v1::SensitivityMethod_IsValid(options.sensitivity())) {
    errors.push_back({path("sensitivity"), "unknown method"});
  }
  return errors;
}

}  // namespace pfem::server
