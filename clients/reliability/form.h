#pragma once
// FORM: the design point u* = argmin ||u|| subject to G(u) = 0 in standard normal space,
// beta = alpha . u* with alpha = -grad G / ||grad G|| at u*, and pf = Phi(-beta).
//   kIhlrf   improved HL-RF (Zhang & Der Kiureghian 1995): HL-RF direction with an Armijo
//            line search on the merit function m(u) = ||u||^2 / 2 + c |G(u)|.
//   kSlsqp   NLopt LD_SLSQP on min ||u||^2 / 2 s.t. G(u) = 0 (uses gradients).
//   kCobyla  NLopt LN_COBYLA, the same problem without gradients (a fallback for rough g);
//            the gradient is still used once at the end for alpha.
#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <Eigen/Dense>

#include "clients/reliability/errors.h"
#include "clients/reliability/limit_state.h"
#include "clients/reliability/nataf.h"

namespace pfem::reliability {

enum class FormMethod { kIhlrf, kSlsqp, kCobyla };
std::optional<FormMethod> parse_form_method(std::string_view name);  // "ihlrf", "slsqp", "cobyla"
std::string_view to_string(FormMethod method);

// One design-point iteration, for progress reports.
struct FormIteration {
  int iteration = 0;
  double beta = 0.0;       // ||u|| of the current iterate
  double g = 0.0;          // G at the current iterate
  double step = 0.0;       // line-search step (ihlrf) or 1
  int evaluations = 0;     // calls of g so far
};

struct FormOptions {
  FormMethod method = FormMethod::kIhlrf;
  int max_iterations = 100;       // ihlrf iterations; NLopt methods get 50 x this many evaluations
  // Convergence: |G(u)| <= tolerance |G(u0)| and ||u - (alpha.u) alpha|| <= tolerance max(1, ||u||)
  // (the NLopt methods are allowed 100 x tolerance on the second test: their objective is flat
  // along the surface, so beta is still accurate to about tolerance^2 there). iHL-RF also counts
  // as converged a point where g's jumps hide the rest of the second test from its line search
  // (FormResult::beta_resolution).
  double tolerance = 1e-6;
  double fd_step = 1e-6;          // u-space step of finite-difference gradients (g without gradient)
  std::vector<double> start_u;    // start point in u; empty: the mean point T(mean of x)
  double armijo_a = 0.5;          // ihlrf: sufficient-decrease constant of the line search
  double armijo_b = 0.5;          // ihlrf: step reduction factor
  int max_line_search_steps = 30; // ihlrf
  std::function<void(const FormIteration&)> progress;  // may be empty

  // Every invalid setting, e.g. {"max_iterations", "must be > 0"}.
  std::vector<FieldError> validate() const;
};

struct FormResult {
  bool converged = false;
  std::string message;           // why it stopped
  FormMethod method = FormMethod::kIhlrf;
  int iterations = 0;
  int evaluations = 0;           // calls of g (with or without gradient)
  int gradient_evaluations = 0;  // gradients of g
  double beta = 0.0;             // alpha . u* (negative when the mean point fails)
  double pf = 0.0;               // Phi(-beta)
  Eigen::VectorXd u;             // design point in standard normal space
  Eigen::VectorXd x;             // design point in the original space
  Eigen::VectorXd alpha;         // -grad G / ||grad G|| at u* (positive: demand-like variable)
  Eigen::VectorXd gamma;         // importance vector in x with correlation (Der Kiureghian)
  Eigen::VectorXd gradient_u;    // grad G at u*
  double g = 0.0;                // G(u*)
  // 0 when the design-point tests passed. Else the search stopped where g's jumps (a PFEM
  // response's remeshing decisions) place the limit state only to within this distance in u
  // along alpha, within the tolerance on beta, and u's misalignment with alpha costs beta less:
  // beta is known to about this much (iHL-RF only).
  double beta_resolution = 0.0;
  std::string gradient_source;
};

// Throws ProblemError for invalid options (and whatever the limit state throws).
FormResult run_form(const LimitState& g, const NatafTransform& transform,
                    const FormOptions& options = {});

}  // namespace pfem::reliability
