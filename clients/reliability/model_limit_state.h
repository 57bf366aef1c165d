#pragma once
// A limit state defined by a PFEM simulation (pfem.v1.ModelLimitState):
//   g(x) = threshold - functional(recorder history of the model with parameters set from x)
// Each random variable sets one model parameter (the parameter of the same name, or the one
// `parameters` maps it to); dg/dx_i = -d functional / d parameter_i, from DDM (default) or
// the engine's central FDM, in-process or through a pfem-server's Evaluate.
#include <memory>
#include <string>
#include <vector>

#include "clients/reliability/limit_state.h"
#include "clients/reliability/model_evaluator.h"
#include "clients/reliability/problem_io.h"

namespace pfem::reliability {

class ModelLimitState final : public LimitState {
 public:
  // parameters[i]: the model parameter set by variable i.
  ModelLimitState(std::shared_ptr<const ModelEvaluator> evaluator, FunctionalSpec functional,
                  double threshold, std::vector<std::string> parameters);

  std::size_t num_variables() const override { return parameters_.size(); }
  // Throws LimitStateError with the engine's (or the server's) message when the run fails.
  double evaluate(std::span<const double> x, std::span<double> gradient) const override;
  bool provides_gradient() const override { return true; }
  std::string gradient_source() const override { return evaluator_->gradient_source(); }
  std::optional<SimulationStats> simulation_stats() const override { return evaluator_->stats(); }

  const std::vector<std::string>& parameters() const { return parameters_; }
  const FunctionalSpec& functional() const { return functional_; }
  double threshold() const { return threshold_; }
  const ModelEvaluator& evaluator() const { return *evaluator_; }

 private:
  std::shared_ptr<const ModelEvaluator> evaluator_;
  FunctionalSpec functional_;
  double threshold_;
  std::vector<std::string> parameters_;
};

// The functional of a model limit state (its name must parse: problem_io checked it).
FunctionalSpec limit_state_functional(const pfem::v1::ModelLimitState& m);

// Every problem of a problem's model limit state that needs the model to see: the model's own
// errors (paths "limit_state.model.model.<field>"), an unknown recorder, a bad time window,
// variables that name no model parameter (or two variables on one parameter). Empty for
// expression limit states.
std::vector<FieldError> validate_model_limit_state(const Problem& problem);

// The limit state of a built problem: an ExpressionLimitState, or a ModelLimitState evaluated
// as `options` say (in-process, or through options.server). Throws ProblemError
// (validate_model_limit_state) and LimitStateError (e.g. the server cannot be reached).
std::unique_ptr<LimitState> make_limit_state(const Problem& problem, const EvaluatorOptions& options);

}  // namespace pfem::reliability
