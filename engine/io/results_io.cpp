#include "engine/io/results_io.h"

#include <cstdio>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace pfem {

namespace {
std::string number(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  return buf;
}
std::string quoted(const std::string& s) {
  std::string out = "\"";
  for (char c : s) {
    if (c == '"' || c == '\\') out += '\\', out += c;
    else if (c == '\n') out += "\\n";
    else if (static_cast<unsigned char>(c) < 0x20) out += ' ';
    else out += c;
  }
  return out + "\"";
}
const char* status_name(RunStatus s) {
  return s == RunStatus::kCompleted ? "completed" : s == RunStatus::kFailed ? "failed" : "cancelled";
}
}  // namespace

void write_histories_csv(const Histories& h, const std::filesystem::path& file) {
  std::ofstream out(file);
  if (!out) throw std::runtime_error("cannot write " + file.string());
  out << "time";
  for (const auto& c : h.columns) out << ',' << c;
  out << '\n';
  for (std::size_t i = 0; i < h.time.size(); ++i) {
    out << number(h.time[i]);
    for (double v : h.rows[i]) out << ',' << number(v);
    out << '\n';
  }
  if (!out) throw std::runtime_error("failed writing " + file.string());
}

std::string summary_json(const RunSummary& s) {
  std::ostringstream o;
  o << "{\n"
    << "  \"status\": " << quoted(status_name(s.status)) << ",\n"
    << "  \"message\": " << quoted(s.message) << ",\n"
    << "  \"failed_step\": " << s.failed_step << ",\n"
    << "  \"failed_time\": " << number(s.failed_time) << ",\n"
    << "  \"steps\": " << s.steps << ",\n"
    << "  \"t_end\": " << number(s.t_end) << ",\n"
    << "  \"dt\": " << number(s.dt) << ",\n"
    << "  \"wall_seconds\": " << number(s.wall_seconds) << ",\n"
    << "  \"response_seconds\": " << number(s.response_seconds) << ",\n"
    << "  \"sensitivity_seconds\": " << number(s.sensitivity_seconds) << ",\n"
    << "  \"remesh_seconds\": " << number(s.remesh_seconds) << ",\n"
    << "  \"assemble_seconds\": " << number(s.assemble_seconds) << ",\n"
    << "  \"factorize_seconds\": " << number(s.factorize_seconds) << ",\n"
    << "  \"solve_seconds\": " << number(s.solve_seconds) << ",\n"
    << "  \"newton_iterations\": " << s.newton_iterations << ",\n"
    << "  \"factorizations\": " << s.factorizations << ",\n"
    << "  \"substeps\": " << s.substeps << ",\n"
    << "  \"deformation_substeps\": " << s.deformation_substeps << ",\n"
    << "  \"removed_particles\": " << s.removed_particles << ",\n"
    << "  \"inserted_particles\": " << s.inserted_particles << ",\n"
    << "  \"left_domain\": " << s.left_domain << ",\n"
    << "  \"fluid_area_max_drift\": " << number(s.fluid_area_max_drift) << ",\n"
    << "  \"particles\": " << s.particles << ",\n"
    << "  \"max_elements\": " << s.max_elements << ",\n"
    << "  \"fluid_area_initial\": " << number(s.fluid_area_initial) << ",\n"
    << "  \"fluid_area_final\": " << number(s.fluid_area_final) << ",\n"
    << "  \"fluid_area_left\": " << number(s.fluid_area_left) << ",\n"
    << "  \"sensitivity_method\": " << quoted(s.sensitivity_method) << ",\n"
    << "  \"warnings\": [";
  for (std::size_t i = 0; i < s.warnings.size(); ++i) o << (i ? ", " : "") << quoted(s.warnings[i]);
  o << "],\n"
    << "  \"parameters\": {";
  for (std::size_t i = 0; i < s.parameters.size(); ++i)
    o << (i ? ", " : "") << quoted(s.parameters[i]) << ": "
      << number(i < s.parameter_values.size() ? s.parameter_values[i] : 0.0);
  o << "}\n}\n";
  return o.str();
}

void write_results(const RunResult& result, const std::filesystem::path& dir) {
  std::filesystem::create_directories(dir);
  write_histories_csv(result.responses, dir / "responses.csv");
  if (!result.sensitivities.columns.empty()) write_histories_csv(result.sensitivities, dir / "sensitivities.csv");
  std::ofstream out(dir / "summary.json");
  out << summary_json(result.summary);
  if (!out) throw std::runtime_error("cannot write " + (dir / "summary.json").string());
}

}  // namespace pfem
