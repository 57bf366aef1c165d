#include "clients/reliability/limit_state.h"

#include <cmath>

namespace pfem::reliability {

ExpressionLimitState::ExpressionLimitState(std::string_view text,
                                           std::vector<std::string> variable_names)
    : names_(std::move(variable_names)), expression_(Expression::parse(text, names_)) {}

double ExpressionLimitState::evaluate(std::span<const double> x, std::span<double> gradient) const {
  return expression_.evaluate(x, gradient);
}

StandardSpaceFunction::StandardSpaceFunction(const LimitState& g, const NatafTransform& transform,
                                             double fd_step)
    : g_(g), transform_(transform), fd_step_(fd_step) {}

std::string StandardSpaceFunction::gradient_source() const {
  return g_.provides_gradient() ? g_.gradient_source() : "finite differences (forward, in u)";
}

double StandardSpaceFunction::value(const Eigen::VectorXd& u) {
  const Eigen::VectorXd x = transform_.to_x(u);
  ++evaluations_;
  return g_.evaluate(std::span<const double>(x.data(), x.size()), {});
}

double StandardSpaceFunction::value_and_gradient(const Eigen::VectorXd& u,
                                                 Eigen::VectorXd& gradient_u) {
  ++gradients_;
  if (!g_.provides_gradient()) {
    const double g0 = value(u);
    gradient_u.resize(size());
    Eigen::VectorXd up = u;
    for (int i = 0; i < size(); ++i) {
      up(i) = u(i) + fd_step_;
      gradient_u(i) = (value(up) - g0) / fd_step_;
      up(i) = u(i);
    }
    return g0;
  }
  Eigen::MatrixXd jacobian;
  const Eigen::VectorXd x = transform_.to_x(u, jacobian);
  Eigen::VectorXd gx(size());
  ++evaluations_;
  const double g0 = g_.evaluate(std::span<const double>(x.data(), x.size()),
                                std::span<double>(gx.data(), gx.size()));
  gradient_u = jacobian.transpose() * gx;
  return g0;
}

}  // namespace pfem::reliability
