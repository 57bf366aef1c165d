#include "wire/convert.h"

#include <cmath>

namespace pfem::wire {

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
  out.set_deformation_substeps(s.deformation_substeps);
  out.set_removed_particles(s.removed_particles);
  out.set_inserted_particles(s.inserted_particles);
  out.set_left_domain(s.left_domain);
  out.set_fluid_area_max_drift(s.fluid_area_max_drift);
  out.set_fluid_area_left(s.fluid_area_left);
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
  out.deformation_substeps = s.deformation_substeps();
  out.removed_particles = s.removed_particles();
  out.inserted_particles = s.inserted_particles();
  out.left_domain = s.left_domain();
  out.fluid_area_max_drift = s.fluid_area_max_drift();
  out.fluid_area_left = s.fluid_area_left();
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

}  // namespace pfem::wire
