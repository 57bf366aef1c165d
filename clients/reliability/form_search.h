#pragma once
// Internal to the FORM implementation: the design-point searches that run_form dispatches to.
#include <string>

#include <Eigen/Dense>

#include "clients/reliability/form.h"
#include "clients/reliability/limit_state.h"

namespace pfem::reliability::detail {

struct SearchOutcome {
  Eigen::VectorXd u;          // last iterate
  bool converged = false;
  std::string message;
  int iterations = 0;
  bool has_gradient = false;  // g and gradient below belong to u
  double g = 0.0;
  Eigen::VectorXd gradient;
  double beta_resolution = 0.0;  // > 0: converged to g's resolution (FormResult::beta_resolution)
};

// The two convergence tests shared by every method: |G| <= tol_g * g_scale and
// ||u - (alpha.u) alpha|| <= tol_alignment * max(1, ||u||), alpha = -grad/||grad||.
bool design_point_converged(const Eigen::VectorXd& u, double g, const Eigen::VectorXd& gradient,
                            double g_scale, double tol_g, double tol_alignment);

SearchOutcome search_ihlrf(StandardSpaceFunction& G, const Eigen::VectorXd& u0,
                           const FormOptions& options);
SearchOutcome search_nlopt(StandardSpaceFunction& G, const Eigen::VectorXd& u0,
                           const FormOptions& options);

}  // namespace pfem::reliability::detail
