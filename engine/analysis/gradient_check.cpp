#include "engine/analysis/gradient_check.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace pfem {

namespace {
// Largest |a - b| over time relative to the largest |b|, for column j.
double relative_difference(const Histories& a, const Histories& b, std::size_t j, double& max_b) {
  double diff = 0.0;
  max_b = 0.0;
  for (std::size_t i = 0; i < std::min(a.rows.size(), b.rows.size()); ++i) {
    diff = std::max(diff, std::abs(a.rows[i][j] - b.rows[i][j]));
    max_b = std::max(max_b, std::abs(b.rows[i][j]));
  }
  if (max_b > 0.0) return diff / max_b;
  return diff > 0.0 ? std::numeric_limits<double>::infinity() : 0.0;
}
}  // namespace

GradientCheck check_gradients(const pfem::v1::Model& model, RunOptions options, bool without_geometric) {
  GradientCheck out;
  options.sensitivity = SensitivityMethod::kDdm;
  options.prepared = prepare_run(model, options);  // validated and built once for both DDM runs
  const RunResult ddm = run(model, options);
  out.ddm = ddm.summary;
  RunResult approximate;
  if (without_geometric) {
    options.drop_geometric_terms = true;
    approximate = run(model, options);
    options.drop_geometric_terms = false;
  }
  options.sensitivity = SensitivityMethod::kFdm;
  options.prepared = prepare_run(model, options, /*validated=*/true);  // without the DDM's seeds
  const RunResult fdm = run(model, options);
  out.fdm = fdm.summary;
  if (ddm.summary.status != RunStatus::kCompleted || fdm.summary.status != RunStatus::kCompleted) return out;

  const auto& s = ddm.summary;
  const std::size_t np = s.parameters.size();
  for (std::size_t j = 0; j < ddm.sensitivities.columns.size(); ++j) {
    GradientCheckRow row;
    row.recorder = ddm.responses.columns[j / np];
    row.parameter = s.parameters[j % np];
    row.ddm = relative_difference(ddm.sensitivities, fdm.sensitivities, j, row.max_fdm);
    for (const auto& r : ddm.sensitivities.rows) row.max_ddm = std::max(row.max_ddm, std::abs(r[j]));
    double max_response = 0.0;
    for (const auto& r : ddm.responses.rows) max_response = std::max(max_response, std::abs(r[j / np]));
    const double theta = std::abs(s.parameter_values[j % np]);
    row.negligible = negligible_sensitivity(std::max(row.max_fdm, row.max_ddm), max_response, theta > 0.0 ? theta : 1.0);
    row.not_a_slope = j < fdm.fdm_spread.size() && fdm.fdm_spread[j] > kFdmParted;
    row.unmoved = max_response == 0.0 && row.max_fdm == 0.0;
    if (without_geometric && approximate.summary.status == RunStatus::kCompleted) {
      double unused = 0.0;
      row.without_geometric = relative_difference(approximate.sensitivities, fdm.sensitivities, j, unused);
    }
    out.rows.push_back(row);
  }
  return out;
}

}  // namespace pfem
