#include "engine/structure/dynamic_solver.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "engine/structure/validation.h"

namespace pfem::structure {

DynamicSolver::DynamicSolver(StructureModel& model, const DynamicOptions& options,
                             const Eigen::VectorXd& v0)
    : model_(model), options_(options), dofs_(model) {
  require_positive(options.dt, "dt");
  if (v0.size() == 0) {
    v_ = Eigen::VectorXd::Zero(model.num_dofs());
  } else if (v0.size() == model.num_dofs()) {
    v_ = dofs_.expand(dofs_.restrict(v0));  // no velocity on supported dofs
  } else {
    throw std::invalid_argument("v0: has " + std::to_string(v0.size()) + " entries, the model " +
                                std::to_string(model.num_dofs()) + " dofs");
  }
}

SolveSummary DynamicSolver::step() {
  const double dt = options_.dt;
  const double t = time_ + dt;
  const double lambda = options_.load_factor ? options_.load_factor(t) : 1.0;
  const Eigen::VectorXd u_n = model_.committed_displacement();
  const Eigen::VectorXd f_ext = lambda * model_.external_load();
  Eigen::VectorXd v = v_;  // predictor: constant velocity

  SolveSummary summary;
  double reference = dofs_.restrict(f_ext).norm();
  bool converged = false;
  for (int it = 0; it <= options_.newton.max_iterations; ++it) {
    model_.set_trial_displacement(u_n + dt * v);
    const Eigen::VectorXd r_global =
        f_ext - model_.mass_times(v - v_) / dt - model_.damping_times(v) - model_.resisting_force();
    const Eigen::VectorXd r = dofs_.restrict(r_global);
    summary.residual_norm = r.norm();
    if (it == 0) reference = std::max(reference, summary.residual_norm);
    if (summary.residual_norm <=
        options_.newton.relative_tolerance * reference + options_.newton.absolute_tolerance) {
      converged = true;
      break;
    }
    if (it == options_.newton.max_iterations) break;
    ++summary.newton_iterations;
    const auto fill = [&](const AddEntry& add) {
      model_.add_mass(add, 1.0 / dt);
      model_.add_damping(add);
      model_.add_tangent(add, dt);
    };
    v += dofs_.expand(solve_free(dofs_, fill, r));
  }
  if (!converged) {
    model_.revert_to_last_commit();
    summary.converged = false;
    summary.steps = steps_;
    summary.message = "dynamic Newton did not converge at t = " + std::to_string(t) +
                      " (residual " + std::to_string(summary.residual_norm) + ")";
    return summary;
  }
  model_.commit();
  v_ = v;
  time_ = t;
  summary.steps = ++steps_;
  return summary;
}

}  // namespace pfem::structure
