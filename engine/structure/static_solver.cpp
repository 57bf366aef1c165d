#include "engine/structure/static_solver.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "engine/structure/free_dofs.h"
#include "engine/structure/validation.h"

namespace pfem::structure {

SolveSummary solve_static(StructureModel& model, const StaticOptions& options) {
  if (options.load_steps < 1)
    throw_invalid("load_steps", "must be >= 1 (got " + std::to_string(options.load_steps) + ")");
  const FreeDofs dofs(model);
  const Eigen::VectorXd load = model.external_load();
  SolveSummary summary;
  for (int k = 1; k <= options.load_steps; ++k) {
    const double lambda =
        options.initial_load_factor + (1.0 - options.initial_load_factor) * k / options.load_steps;
    const Eigen::VectorXd f_ext = dofs.restrict(lambda * load);
    Eigen::VectorXd u = dofs.restrict(model.committed_displacement());
    const Eigen::VectorXd u_fixed = model.committed_displacement() - dofs.expand(u);
    double reference = f_ext.norm();
    bool converged = false;
    std::string failure = "no convergence";
    try {
      for (int it = 0; it <= options.newton.max_iterations; ++it) {
        model.set_trial_displacement(u_fixed + dofs.expand(u));
        const Eigen::VectorXd r = f_ext - dofs.restrict(model.resisting_force());
        summary.residual_norm = r.norm();
        if (!std::isfinite(summary.residual_norm)) break;
        if (it == 0) reference = std::max(reference, summary.residual_norm);
        if (summary.residual_norm <=
            options.newton.relative_tolerance * reference + options.newton.absolute_tolerance) {
          converged = true;
          break;
        }
        if (it == options.newton.max_iterations) break;
        ++summary.newton_iterations;
        u += solve_free(
            dofs, [&](const AddEntry& add) { model.add_tangent(add); }, r);
      }
    } catch (const std::runtime_error& e) {
      failure = e.what();
    }
    if (!converged) {
      model.revert_to_last_commit();
      summary.converged = false;
      summary.message = "static Newton failed at load step " + std::to_string(k) + " (lambda " +
                        std::to_string(lambda) + ", residual " +
                        std::to_string(summary.residual_norm) + "): " + failure;
      return summary;
    }
    model.commit();
    summary.steps = k;
  }
  return summary;
}

}  // namespace pfem::structure
