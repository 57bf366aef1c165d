#include "server/convert.h"

#include <cmath>
#include <set>
#include <sstream>

namespace pfem::server {

pfem::v1::Histories to_proto(const Histories& h) {
  pfem::v1::Histories out;
  out.mutable_time()->Assign(h.time.begin(), h.time.end());
  for (std::size_t j = 0; j < h.columns.size(); ++j) {
    auto* column = out.add_columns();
    column->set_name(h.columns[j]);
    column->mutable_values()->Reserve(static_cast<int>(h.rows.size()));
    for (const auto& row : h.rows) column->add_values(j < row.size() ? row[j] : std::nan(""));
  }
  return out;
}

Histories from_proto(const pfem::v1::Histories& h) {
  Histories out;
  out.time.assign(h.time().begin(), h.time().end());
  for (const auto& c : h.columns()) out.columns.push_back(c.name());
  out.rows.assign(out.time.size(), std::vector<double>(out.columns.size(), std::nan("")));
  for (int j = 0; j < h.columns_size(); ++j) {
    const auto& values = h.columns(j).values();
    for (int i = 0; i < values.size() && i < static_cast<int>(out.rows.size()); ++i) {
      out.rows[i][j] = values[i];
    }
  }
  return out;
}

pfem::v1::Summary to_proto(const RunSummary& s) {
  pfem::v1::Summary out;
  switch (s.status) {
    case RunStatus::kCompleted: out.set_status(pfem::v1::RUN_STATUS_COMPLETED); break;
    case RunStatus::kFailed: out.set_status(pfem::v1::RUN_STATUS_FAILED); break;
    case RunStatus::kCancelled: out.set_status(pfem::v1::RUN_STATUS_CANCELLED); break;
  }
  out.set_message(s.message);
  out.set_failed_step(s.failed_step);
  out.set_failed_time(s.failed_time);
  out.set_steps(s.steps);
  out.set_t_end(s.t_end);
  out.set_dt(s.dt);
  out.set_wall_seconds(s.wall_seconds);
  out.set_response_seconds(s.response_seconds);
  out.set_sensitivity_seconds(s.sensitivity_seconds);
  out.set_remesh_seconds(s.remesh_seconds);
  out.set_assemble_seconds(s.assemble_seconds);
  out.set_factorize_seconds(s.factorize_seconds);
  out.set_solve_seconds(s.solve_seconds);
  out.set_newton_iterations(s.newton_iterations);
  out.set_factorizations(s.factorizations);
  out.set_substeps(s.substeps);
  out.set_removed_particles(s.removed_particles);
  out.set_inserted_particles(s.inserted_particles);
  out.set_left_domain(s.left_domain);
  out.set_fluid_area_max_drift(s.fluid_area_max_drift);
  for (const auto& w : s.warnings) out.add_warnings(w);
  out.set_particles(s.particles);
  out.set_max_elements(s.max_elements);
  out.set_fluid_area_initial(s.fluid_area_initial);
  out.set_fluid_area_final(s.fluid_area_final);
  out.set_sensitivity_method(s.sensitivity_method);
  for (const auto& p : s.parameters) out.add_parameters(p);
  out.mutable_parameter_values()->Assign(s.parameter_values.begin(), s.parameter_values.end());
  return out;
}

RunSummary from_proto(const pfem::v1::Summary& s) {
  RunSummary out;
  switch (s.status()) {
    case pfem::v1::RUN_STATUS_FAILED: out.status = RunStatus::kFailed; break;
    case pfem::v1::RUN_STATUS_CANCELLED: out.status = RunStatus::kCancelled; break;
    default: out.status = RunStatus::kCompleted; break;
  }
  out.message = s.message();
  out.failed_step = s.failed_step();
  out.failed_time = s.failed_time();
  out.steps = s.steps();
  out.t_end = s.t_end();
  out.dt = s.dt();
  out.wall_seconds = s.wall_seconds();
  out.response_seconds = s.response_seconds();
  out.sensitivity_seconds = s.sensitivity_seconds();
  out.remesh_seconds = s.remesh_seconds();
  out.assemble_seconds = s.assemble_seconds();
  out.factorize_seconds = s.factorize_seconds();
  out.solve_seconds = s.solve_seconds();
  out.newton_iterations = s.newton_iterations();
  out.factorizations = s.factorizations();
  out.substeps = s.substeps();
  out.removed_particles = s.removed_particles();
  out.inserted_particles = s.inserted_particles();
  out.left_domain = s.left_domain();
  out.fluid_area_max_drift = s.fluid_area_max_drift();
  out.warnings.assign(s.warnings().begin(), s.warnings().end());
  out.particles = s.particles();
  out.max_elements = s.max_elements();
  out.fluid_area_initial = s.fluid_area_initial();
  out.fluid_area_final = s.fluid_area_final();
  out.sensitivity_method = s.sensitivity_method();
  out.parameters.assign(s.parameters().begin(), s.parameters().end());
  out.parameter_values.assign(s.parameter_values().begin(), s.parameter_values().end());
  return out;
}

pfem::v1::Result to_proto(const RunResult& r) {
  pfem::v1::Result out;
  *out.mutable_summary() = to_proto(r.summary);
  *out.mutable_responses() = to_proto(r.responses);
  *out.mutable_sensitivities() = to_proto(r.sensitivities);
  return out;
}

RunResult from_proto(const pfem::v1::Result& r) {
  RunResult out;
  out.summary = from_proto(r.summary());
  out.responses = from_proto(r.responses());
  out.sensitivities = from_proto(r.sensitivities());
  return out;
}

pfem::v1::Progress to_proto(const Progress& p) {
  pfem::v1::Progress out;
  out.set_step(p.step);
  out.set_total_steps(p.total_steps);
  out.set_time(p.time);
  out.set_t_end(p.t_end);
  out.set_newton_iterations(p.newton_iterations);
  out.set_elapsed_seconds(p.elapsed_seconds);
  out.set_remaining_seconds(p.remaining_seconds);
  return out;
}

SensitivityMethod from_proto(pfem::v1::SensitivityMethod method, SensitivityMethod fallback) {
  switch (method) {
    case pfem::v1::SENSITIVITY_METHOD_NONE: return SensitivityMethod::kNone;
    case pfem::v1::SENSITIVITY_METHOD_DDM: return SensitivityMethod::kDdm;
    case pfem::v1::SENSITIVITY_METHOD_FDM: return SensitivityMethod::kFdm;
    default: return fallback;
  }
}

pfem::v1::SensitivityMethod to_proto(SensitivityMethod method) {
  switch (method) {
    case SensitivityMethod::kNone: return pfem::v1::SENSITIVITY_METHOD_NONE;
    case SensitivityMethod::kDdm: return pfem::v1::SENSITIVITY_METHOD_DDM;
    case SensitivityMethod::kFdm: return pfem::v1::SENSITIVITY_METHOD_FDM;
  }
  return pfem::v1::SENSITIVITY_METHOD_UNSPECIFIED;
}

RunOptions to_run_options(const pfem::v1::RunOptions& options, SensitivityMethod fallback) {
  RunOptions out;
  if (options.has_t_end()) out.t_end = options.t_end();
  if (options.has_dt()) out.dt = options.dt();
  out.sensitivity = from_proto(options.sensitivity(), fallback);
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
