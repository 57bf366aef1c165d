#include "clients/reliability/model_limit_state.h"

#include <algorithm>
#include <cmath>
#include <map>

#include "engine/io/model_io.h"

namespace pfem::reliability {

namespace {

std::string list(const std::vector<std::string>& names) {
  if (names.empty()) return "none";
  std::string out;
  for (const auto& n : names) out += (out.empty() ? "" : ", ") + n;
  return out;
}

// The model parameter of each variable (empty when there are errors).
std::vector<std::string> variable_parameters(const Problem& problem, std::vector<FieldError>& errors) {
  const auto& m = problem.message.limit_state().model();
  const std::string path = "limit_state.model";
  const auto model_params = model_parameter_names(m.model());
  std::vector<std::string> out;
  std::map<std::string, std::string> used;  // parameter -> variable
  for (std::size_t i = 0; i < problem.names.size(); ++i) {
    const std::string& var = problem.names[i];
    const auto it = m.parameters().find(var);
    const bool mapped = it != m.parameters().end();
    const std::string param = mapped ? it->second : var;
    const std::string where = mapped ? path + ".parameters[\"" + var + "\"]"
                                     : "variables[" + std::to_string(i) + "].name";
    if (std::find(model_params.begin(), model_params.end(), param) == model_params.end()) {
      errors.push_back({where, mapped ? "unknown model parameter '" + param + "' (the model's parameters: " +
                                            list(model_params) + ")"
                                      : "the model has no parameter '" + var +
                                            "' (map the variable to one in " + path +
                                            ".parameters; the model's parameters: " +
                                            list(model_params) + ")"});
    } else if (used.count(param)) {
      errors.push_back({where, "model parameter '" + param + "' is already set by variable '" +
                                   used[param] + "'"});
    } else {
      used[param] = var;
    }
    out.push_back(param);
  }
  return out;
}

}  // namespace

ModelLimitState::ModelLimitState(std::shared_ptr<const ModelEvaluator> evaluator,
                                 FunctionalSpec functional, double threshold,
                                 std::vector<std::string> parameters)
    : evaluator_(std::move(evaluator)),
      functional_(std::move(functional)),
      threshold_(threshold),
      parameters_(std::move(parameters)) {}

double ModelLimitState::evaluate(std::span<const double> x, std::span<double> gradient) const {
  const bool with_gradient = !gradient.empty();
  ModelEvaluation e;
  try {
    e = evaluator_->evaluate(parameters_, x, {functional_}, with_gradient);
  } catch (const ModelEvaluationError& error) {
    throw LimitStateError(error.what());
  }
  const FunctionalValue& f = e.values.at(0);
  if (with_gradient) {
    for (std::size_t i = 0; i < parameters_.size(); ++i) gradient[i] = -f.gradient.at(i);
  }
  return threshold_ - f.value;
}

FunctionalSpec limit_state_functional(const pfem::v1::ModelLimitState& m) {
  return functional_spec_of(m, *parse_functional_name(m.functional()));
}

std::vector<FieldError> validate_model_limit_state(const Problem& problem) {
  std::vector<FieldError> errors;
  if (problem.limit_state_kind != LimitStateKind::kModel) return errors;
  const auto& m = problem.message.limit_state().model();
  const std::string path = "limit_state.model";
  for (const auto& e : pfem::validate_model(m.model())) {
    errors.push_back({path + ".model" + (e.path.empty() ? "" : "." + e.path), e.message});
  }
  const auto recorders = model_recorder_names(m.model());
  if (!m.recorder().empty() &&
      std::find(recorders.begin(), recorders.end(), m.recorder()) == recorders.end()) {
    errors.push_back({path + ".recorder", "unknown recorder '" + m.recorder() +
                                              "' (the model's recorders: " + list(recorders) + ")"});
  }
  if (!std::isfinite(m.threshold())) errors.push_back({path + ".threshold", "must be finite"});
  if (parse_functional_name(m.functional())) {
    if (auto bad = check_functional_window(limit_state_functional(m))) {
      errors.push_back({path + "." + bad->first, bad->second});
    }
  }
  variable_parameters(problem, errors);
  return errors;
}

std::unique_ptr<LimitState> make_limit_state(const Problem& problem, const EvaluatorOptions& options) {
  if (problem.limit_state_kind == LimitStateKind::kExpression) {
    return std::make_unique<ExpressionLimitState>(problem.expression, problem.names);
  }
  if (auto errors = validate_model_limit_state(problem); !errors.empty()) {
    throw ProblemError(std::move(errors));
  }
  const auto& m = problem.message.limit_state().model();
  std::vector<FieldError> unused;
  std::vector<std::string> params = variable_parameters(problem, unused);
  FunctionalSpec spec = limit_state_functional(m);
  std::shared_ptr<const ModelEvaluator> evaluator;
  try {
    evaluator = make_evaluator(m.model(), options, "limit_state.model.model");
  } catch (const ModelEvaluationError& e) {
    throw LimitStateError(e.what());
  }
  return std::make_unique<ModelLimitState>(std::move(evaluator), std::move(spec), m.threshold(),
                                           std::move(params));
}

}  // namespace pfem::reliability
