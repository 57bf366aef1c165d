#pragma once
// The limit-state seam: g(x) and, when asked, its gradient from one call (Ceres-style: an
// empty gradient span means "not needed"). Failure is g < 0.
//
// Implementations: ExpressionLimitState (exact gradients by reverse-mode AD over the parsed
// expression) and ModelLimitState (clients/reliability/model_limit_state.h: a PFEM run with
// DDM or FDM gradients, in-process or through the gRPC service).
#include <memory>
#include <optional>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

#include <Eigen/Dense>

#include "clients/reliability/expression.h"
#include "clients/reliability/nataf.h"
#include "clients/reliability/simulation_stats.h"

namespace pfem::reliability {

// Thrown by LimitState::evaluate when g cannot be evaluated at x (e.g. a failed simulation).
class LimitStateError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class LimitState {
 public:
  virtual ~LimitState() = default;
  virtual std::size_t num_variables() const = 0;
  // g(x). When `gradient` is non-empty (size num_variables()) it also receives dg/dx; pass an
  // empty span when the gradient is not needed. Throws LimitStateError on failure. Must be
  // safe to call concurrently from several threads.
  virtual double evaluate(std::span<const double> x, std::span<double> gradient) const = 0;
  // False when evaluate() cannot fill a gradient; callers then use finite differences.
  virtual bool provides_gradient() const = 0;
  // Where the gradients come from, for reports: e.g. "exact (expression AD)".
  virtual std::string gradient_source() const = 0;
  // What the simulations behind g cost so far; nullopt for limit states without simulations.
  virtual std::optional<SimulationStats> simulation_stats() const { return std::nullopt; }
};

class ExpressionLimitState final : public LimitState {
 public:
  // Throws ExpressionError (with the column) for a bad expression or an unknown name.
  ExpressionLimitState(std::string_view text, std::vector<std::string> variable_names);

  std::size_t num_variables() const override { return names_.size(); }
  double evaluate(std::span<const double> x, std::span<double> gradient) const override;
  bool provides_gradient() const override { return true; }
  std::string gradient_source() const override { return "exact (expression AD)"; }
  const Expression& expression() const { return expression_; }

 private:
  std::vector<std::string> names_;
  Expression expression_;
};

// G(u) = g(T^-1(u)) in standard normal space with evaluation counts; gradients from the
// limit state mapped through the transform's Jacobian (grad_u G = J^T grad_x g), or forward
// finite differences of step `fd_step` in u when the limit state has no gradient.
// Not thread-safe (it counts); make one per thread.
class StandardSpaceFunction {
 public:
  StandardSpaceFunction(const LimitState& g, const NatafTransform& transform, double fd_step = 1e-6);

  int size() const { return transform_.size(); }
  double value(const Eigen::VectorXd& u);
  double value_and_gradient(const Eigen::VectorXd& u, Eigen::VectorXd& gradient_u);

  int evaluations() const { return evaluations_; }           // calls of g (with or without gradient)
  int gradient_evaluations() const { return gradients_; }    // gradients computed
  std::string gradient_source() const;
  const NatafTransform& transform() const { return transform_; }
  const LimitState& limit_state() const { return g_; }

 private:
  const LimitState& g_;
  const NatafTransform& transform_;
  double fd_step_;
  int evaluations_ = 0;
  int gradients_ = 0;
};

}  // namespace pfem::reliability
