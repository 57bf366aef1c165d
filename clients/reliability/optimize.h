#pragma once
// Gradient-based design optimisation of a PFEM model (the library behind `pfem-optimize`):
//   minimise f(x) subject to l_j <= c_j(x) <= u_j and lower <= x <= upper,
// x = values of the model's named parameters; f and c_j are functionals of model recorders
// (value and gradient from one simulation with DDM or FDM sensitivities, in-process or through
// a pfem-server's Evaluate: clients/reliability/model_evaluator.h) or expressions of x (exact
// gradients, clients/reliability/expression.h). NLopt's LD_SLSQP (default) or LD_MMA works on
// the design scaled to [0, 1] per variable, the objective divided by |f(x0)| and each
// constraint written as (c - u) / |u| <= 0 (or (l - c) / |l| <= 0; by 1 when the bound is 0).
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "clients/reliability/errors.h"
#include "clients/reliability/expression.h"
#include "clients/reliability/model_evaluator.h"
#include "pfem/v1/optimization.pb.h"

namespace pfem::optimize {

using reliability::FieldError;
using reliability::ProblemError;

enum class Algorithm { kSlsqp, kMma };
std::optional<Algorithm> parse_algorithm(std::string_view name);  // "slsqp", "mma"
std::string_view to_string(Algorithm algorithm);

// An objective or constraint quantity: an expression of the design variables, or the
// functional `functional` (an index into Problem::functionals) of a model recorder.
struct Quantity {
  std::string text;                               // for reports: "width * depth", "max_abs(tip_ux)"
  std::optional<reliability::Expression> expression;
  int functional = -1;
};

struct ConstraintSpec {
  std::string name;
  Quantity quantity;
  std::optional<double> upper;
  std::optional<double> lower;
};

// A validated problem.
struct Problem {
  std::string name;
  std::string description;
  pfem::v1::Model model;
  std::vector<std::string> names;   // design variables = model parameters, in file order
  std::vector<double> lower, upper, initial;
  Quantity objective;
  bool maximize = false;
  std::vector<ConstraintSpec> constraints;
  std::vector<FunctionalSpec> functionals;  // distinct functionals, evaluated by one run
  Algorithm algorithm = Algorithm::kSlsqp;
  int max_evaluations = 40;
  double xtol_rel = 1e-4;
  double ftol_rel = 1e-6;
  double constraint_tolerance = 1e-3;
};

// Parses proto3 JSON (unknown fields are errors). Throws ProblemError naming the field.
pfem::v1::OptimizationProblem parse_problem_json(std::string_view json);
pfem::v1::OptimizationProblem read_problem_file(const std::filesystem::path& path);
// Every problem, with field paths ("variables[0].lower: is required"); empty when valid.
std::vector<FieldError> validate_problem(const pfem::v1::OptimizationProblem& message);
// Validates and builds. Throws ProblemError with every error.
Problem build_problem(const pfem::v1::OptimizationProblem& message);

// One evaluation of the design (one model run when the problem has functionals).
struct Evaluation {
  int index = 0;                      // 1, 2, ...
  std::vector<double> x;
  double objective = 0.0;
  std::vector<double> objective_gradient;              // d f / d x
  std::vector<double> constraints;                     // c_j(x)
  std::vector<std::vector<double>> constraint_gradients;  // d c_j / d x
  double max_violation = 0.0;         // largest violation relative to |bound| (0: feasible)
  double seconds = 0.0;               // wall time since the start
};

struct OptimizeOptions {
  std::function<void(const Evaluation&)> progress;  // after each evaluation; may be empty
};

struct OptimizeResult {
  bool converged = false;       // NLopt stopped on a tolerance at a feasible design
  std::string message;          // why it stopped
  std::string nlopt_result;     // e.g. "XTOL_REACHED"
  Evaluation initial;           // at the start point
  Evaluation best;              // at the design returned
  std::vector<Evaluation> history;
  reliability::SimulationStats simulations;
  std::string gradient_source;
  double wall_seconds = 0.0;
};

// Runs the optimisation. Throws reliability::ModelEvaluationError when the model cannot be
// evaluated at the start point; a failure later stops the search and is reported in message.
OptimizeResult optimize(const Problem& problem, const reliability::ModelEvaluator& evaluator,
                        const OptimizeOptions& options = {});

// DIR/history.csv: evaluation,seconds,<x...>,objective,<constraints...>,max_violation,
// d<objective>/d<x>...,d<constraint>/d<x>...
std::string history_csv(const Problem& problem, const OptimizeResult& result);
// DIR/result.json: problem, algorithm, converged, message, nlopt_result, evaluations,
// gradient_source, x {name: value}, initial_x, objective, initial_objective,
// objective_gradient, constraints [{name, value, upper, lower, active}], max_violation,
// simulations {evaluations, gradient_evaluations, runs, cached, seconds}, wall_seconds.
std::string result_json(const Problem& problem, const OptimizeResult& result);
std::string summary_text(const Problem& problem, const OptimizeResult& result);

}  // namespace pfem::optimize
