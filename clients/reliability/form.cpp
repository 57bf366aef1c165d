#include "clients/reliability/form.h"

#include <cmath>
#include <limits>

#include "clients/reliability/form_search.h"

namespace pfem::reliability {

std::optional<FormMethod> parse_form_method(std::string_view name) {
  if (name == "ihlrf") return FormMethod::kIhlrf;
  if (name == "slsqp") return FormMethod::kSlsqp;
  if (name == "cobyla") return FormMethod::kCobyla;
  return std::nullopt;
}

std::string_view to_string(FormMethod method) {
  switch (method) {
    case FormMethod::kIhlrf: return "ihlrf";
    case FormMethod::kSlsqp: return "slsqp";
    case FormMethod::kCobyla: return "cobyla";
  }
  return "unknown";
}

std::vector<FieldError> FormOptions::validate() const {
  std::vector<FieldError> errors;
  if (max_iterations <= 0) errors.push_back({"max_iterations", "must be > 0"});
  if (!(tolerance > 0 && tolerance < 1)) errors.push_back({"tolerance", "must be in (0, 1)"});
  if (!(fd_step > 0)) errors.push_back({"fd_step", "must be > 0"});
  if (!(armijo_a > 0 && armijo_a < 1)) errors.push_back({"armijo_a", "must be in (0, 1)"});
  if (!(armijo_b > 0 && armijo_b < 1)) errors.push_back({"armijo_b", "must be in (0, 1)"});
  if (max_line_search_steps <= 0) errors.push_back({"max_line_search_steps", "must be > 0"});
  for (std::size_t i = 0; i < start_u.size(); ++i) {
    if (!std::isfinite(start_u[i])) {
      errors.push_back({"start_u[" + std::to_string(i) + "]", "must be finite"});
    }
  }
  return errors;
}

FormResult run_form(const LimitState& g, const NatafTransform& transform,
                    const FormOptions& options) {
  auto errors = options.validate();
  const int n = transform.size();
  if (!options.start_u.empty() && static_cast<int>(options.start_u.size()) != n) {
    errors.push_back({"start_u", "must have one value per variable (" + std::to_string(n) + ")"});
  }
  if (static_cast<int>(g.num_variables()) != n) {
    errors.push_back({"limit_state", "has " + std::to_string(g.num_variables()) +
                                         " variables, the transform " + std::to_string(n)});
  }
  if (!errors.empty()) throw ProblemError(std::move(errors));

  Eigen::VectorXd u0(n);
  if (options.start_u.empty()) {
    Eigen::VectorXd mean(n);
    for (int i = 0; i < n; ++i) mean(i) = transform.marginals()[i].mean();
    u0 = mean.allFinite() ? transform.to_u(mean) : Eigen::VectorXd::Zero(n);
  } else {
    u0 = Eigen::Map<const Eigen::VectorXd>(options.start_u.data(), n);
  }

  StandardSpaceFunction G(g, transform, options.fd_step);
  const detail::SearchOutcome s = options.method == FormMethod::kIhlrf
                                      ? detail::search_ihlrf(G, u0, options)
                                      : detail::search_nlopt(G, u0, options);
  FormResult r;
  r.method = options.method;
  r.converged = s.converged;
  r.message = s.message;
  r.iterations = s.iterations;
  r.u = s.u;
  r.g = s.g;
  r.gradient_u = s.gradient;
  r.beta_resolution = s.beta_resolution;
  const double gn = s.has_gradient ? s.gradient.norm() : 0.0;
  r.alpha = gn > 0 ? Eigen::VectorXd(-s.gradient / gn) : Eigen::VectorXd::Zero(n);
  // Without a gradient (g not finite, or flat) there is no design point: beta and pf are NaN
  // (null in result.json), not the 0 and 0.5 of a zero alpha.
  const bool defined = gn > 0 && std::isfinite(gn) && std::isfinite(s.g);
  r.beta = defined ? r.alpha.dot(r.u) : std::numeric_limits<double>::quiet_NaN();
  r.pf = defined ? standard_normal_cdf(-r.beta) : std::numeric_limits<double>::quiet_NaN();
  Eigen::MatrixXd jacobian;
  r.x = transform.to_x(r.u, jacobian);
  // gamma = alpha^T J_ux D / ||.||, D = diag of the standard deviations of the linearised x.
  r.gamma = r.alpha;
  Eigen::FullPivLU<Eigen::MatrixXd> lu(jacobian);
  if (lu.isInvertible()) {
    const Eigen::MatrixXd jux = lu.inverse();
    const Eigen::VectorXd d = (jacobian * jacobian.transpose()).diagonal().cwiseSqrt();
    const Eigen::VectorXd gamma = (r.alpha.transpose() * jux * d.asDiagonal()).transpose();
    if (gamma.norm() > 0) r.gamma = gamma / gamma.norm();
  }
  r.evaluations = G.evaluations();
  r.gradient_evaluations = G.gradient_evaluations();
  r.gradient_source = G.gradient_source();
  return r;
}

}  // namespace pfem::reliability
