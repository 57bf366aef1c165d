#include "clients/reliability/optimize.h"

#include <google/protobuf/util/json_util.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <exception>
#include <fstream>
#include <map>
#include <set>
#include <tuple>
#include <sstream>

#include <nlopt.hpp>

#include "clients/reliability/json_writer.h"
#include "clients/reliability/problem_io.h"
#include "engine/base/json_errors.h"
#include "engine/io/model_io.h"

namespace pfem::optimize {

namespace rel = pfem::reliability;

std::optional<Algorithm> parse_algorithm(std::string_view name) {
  if (name == "slsqp") return Algorithm::kSlsqp;
  if (name == "mma") return Algorithm::kMma;
  return std::nullopt;
}

std::string_view to_string(Algorithm algorithm) {
  return algorithm == Algorithm::kSlsqp ? "slsqp" : "mma";
}

namespace {

const char* kFunctionalNames = "at_time, max, min, max_abs, final";

std::string list(const std::vector<std::string>& names) {
  if (names.empty()) return "none";
  std::string out;
  for (const auto& n : names) out += (out.empty() ? "" : ", ") + n;
  return out;
}

bool contains(const std::vector<std::string>& v, const std::string& s) {
  return std::find(v.begin(), v.end(), s) != v.end();
}

// Checks one quantity; fills q (and adds its functional to `functionals`) when valid.
void check_quantity(const pfem::v1::DesignQuantity& m, const std::string& path,
                    const std::vector<std::string>& names, const std::vector<std::string>& recorders,
                    bool model_ok, std::vector<FieldError>& errors, Quantity* q,
                    std::vector<FunctionalSpec>* functionals) {
  const bool has_expression = m.expression().find_first_not_of(" \t\r\n") != std::string::npos;
  const bool has_functional = !m.recorder().empty() || !m.functional().empty() || m.has_time() ||
                              m.has_window_start() || m.has_window_end();
  if (has_expression && has_functional) {
    errors.push_back({path, "give either expression or recorder with functional, not both"});
    return;
  }
  if (!has_expression && !has_functional) {
    errors.push_back({path, "is required: {\"expression\": \"...\"} or {\"recorder\": \"...\", "
                            "\"functional\": \"max_abs\"}"});
    return;
  }
  if (has_expression) {
    try {
      auto e = rel::Expression::parse(m.expression(), names);
      if (q) {
        q->text = m.expression();
        q->expression.emplace(std::move(e));
      }
    } catch (const rel::ExpressionError& e) {
      errors.push_back({path + ".expression", e.what()});
    }
    return;
  }
  const std::size_t before = errors.size();
  if (m.recorder().empty()) {
    errors.push_back({path + ".recorder", "is required with functional"});
  } else if (model_ok && !contains(recorders, m.recorder())) {
    errors.push_back({path + ".recorder", "unknown recorder '" + m.recorder() +
                                              "' (the model's recorders: " + list(recorders) + ")"});
  }
  std::optional<FunctionalKind> kind;
  if (m.functional().empty()) {
    errors.push_back({path + ".functional", std::string("is required (one of ") + kFunctionalNames + ")"});
  } else if (!(kind = rel::parse_functional_name(m.functional()))) {
    errors.push_back({path + ".functional", "unknown functional '" + m.functional() +
                                                "' (expected one of " + kFunctionalNames + ")"});
  } else if (*kind == FunctionalKind::kValueAt && !m.has_time()) {
    errors.push_back({path + ".time", "is required for at_time"});
  } else if (*kind != FunctionalKind::kValueAt && m.has_time()) {
    errors.push_back({path + ".time", "only used with at_time"});
  } else if (m.has_time() && !(std::isfinite(m.time()) && m.time() >= 0)) {
    errors.push_back({path + ".time", "must be >= 0"});
  }
  FunctionalSpec spec;
  if (kind) {
    spec = rel::functional_spec_of(m, *kind);
    if (auto bad = check_functional_window(spec)) errors.push_back({path + "." + bad->first, bad->second});
  }
  if (errors.size() != before || !q) return;
  q->text = rel::functional_text(spec);
  for (std::size_t i = 0; i < functionals->size(); ++i) {
    const auto& f = (*functionals)[i];
    if (f.recorder == spec.recorder && f.kind == spec.kind && f.time == spec.time &&
        f.window_start == spec.window_start && f.window_end == spec.window_end) {
      q->functional = static_cast<int>(i);
      return;
    }
  }
  q->functional = static_cast<int>(functionals->size());
  functionals->push_back(spec);
}

std::vector<FieldError> check(const pfem::v1::OptimizationProblem& msg, Problem* out) {
  std::vector<FieldError> errors;
  Problem p;
  p.name = msg.name();
  p.description = msg.description();

  // The model.
  bool model_ok = msg.has_model();
  if (!msg.has_model()) {
    errors.push_back({"model", "is required (a pfem.v1.Model, the `pfem run` schema)"});
  } else {
    for (const auto& e : pfem::validate_model(msg.model())) {
      errors.push_back({"model" + (e.path.empty() ? "" : "." + e.path), e.message});
      model_ok = false;
    }
    p.model = msg.model();
  }
  const auto params = rel::model_parameter_names(msg.model());
  const auto recorders = rel::model_recorder_names(msg.model());

  // Design variables.
  if (msg.variables_size() == 0) errors.push_back({"variables", "at least one design variable is required"});
  for (int i = 0; i < msg.variables_size(); ++i) {
    const auto& v = msg.variables(i);
    const std::string path = "variables[" + std::to_string(i) + "]";
    const std::size_t before = errors.size();
    if (v.name().empty()) {
      errors.push_back({path + ".name", "is required (a model parameter)"});
    } else if (contains(p.names, v.name())) {
      errors.push_back({path + ".name", "'" + v.name() + "' is already a design variable"});
    } else if (msg.has_model() && !contains(params, v.name())) {
      errors.push_back({path + ".name", "the model has no parameter '" + v.name() +
                                            "' (the model's parameters: " + list(params) + ")"});
    }
    for (const auto& [field, has, value] :
         {std::tuple{"lower", v.has_lower(), v.lower()}, std::tuple{"upper", v.has_upper(), v.upper()}}) {
      if (!has) {
        errors.push_back({path + "." + field, "is required"});
      } else if (!std::isfinite(value)) {
        errors.push_back({path + "." + field, "must be finite"});
      }
    }
    if (v.has_lower() && v.has_upper() && !(v.lower() < v.upper())) {
      errors.push_back({path + ".upper", "must be > lower"});
    }
    if (errors.size() != before) {
      p.names.push_back(v.name());
      continue;
    }
    double x0 = 0.0;
    if (v.has_initial()) {
      x0 = v.initial();
      if (!(x0 >= v.lower() && x0 <= v.upper())) {
        errors.push_back({path + ".initial", "must be within [lower, upper]"});
      }
    } else if (model_ok) {
      const auto value = rel::model_parameter_value(msg.model(), v.name());
      if (!value) {
        errors.push_back({path + ".initial", "is required (the model gives no value for '" + v.name() + "')"});
      } else if (!(*value >= v.lower() && *value <= v.upper())) {
        errors.push_back({path + ".initial", "is required: the model's value " + rel::JsonWriter::number(*value) +
                                                 " is outside [lower, upper]"});
      } else {
        x0 = *value;
      }
    }
    p.names.push_back(v.name());
    p.lower.push_back(v.lower());
    p.upper.push_back(v.upper());
    p.initial.push_back(x0);
  }

  // Objective and constraints.
  if (!msg.has_objective()) {
    errors.push_back({"objective", "is required: {\"quantity\": {...}}"});
  } else {
    check_quantity(msg.objective().quantity(), "objective.quantity", p.names, recorders, model_ok,
                   errors, &p.objective, &p.functionals);
    p.maximize = msg.objective().maximize();
  }
  std::set<std::string> constraint_names;
  for (int j = 0; j < msg.constraints_size(); ++j) {
    const auto& c = msg.constraints(j);
    const std::string path = "constraints[" + std::to_string(j) + "]";
    ConstraintSpec spec;
    spec.name = c.name().empty() ? "c" + std::to_string(j) : c.name();
    if (!constraint_names.insert(spec.name).second) {
      errors.push_back({path + ".name", "'" + spec.name + "' is already the name of a constraint"});
    }
    check_quantity(c.quantity(), path + ".quantity", p.names, recorders, model_ok, errors,
                   &spec.quantity, &p.functionals);
    if (!c.has_upper() && !c.has_lower()) {
      errors.push_back({path, "give upper and/or lower (quantity <= upper, quantity >= lower)"});
    }
    if (c.has_upper() && !std::isfinite(c.upper())) errors.push_back({path + ".upper", "must be finite"});
    if (c.has_lower() && !std::isfinite(c.lower())) errors.push_back({path + ".lower", "must be finite"});
    if (c.has_upper() && c.has_lower() && !(c.lower() <= c.upper())) {
      errors.push_back({path + ".upper", "must be >= lower"});
    }
    if (c.has_upper()) spec.upper = c.upper();
    if (c.has_lower()) spec.lower = c.lower();
    p.constraints.push_back(std::move(spec));
  }

  // Options.
  const auto& o = msg.options();
  if (!o.algorithm().empty()) {
    if (const auto a = parse_algorithm(o.algorithm())) {
      p.algorithm = *a;
    } else {
      errors.push_back({"options.algorithm", "unknown algorithm '" + o.algorithm() + "' (expected slsqp or mma)"});
    }
  }
  if (o.has_max_evaluations()) {
    if (o.max_evaluations() <= 0) errors.push_back({"options.max_evaluations", "must be > 0"});
    p.max_evaluations = o.max_evaluations();
  }
  const auto positive = [&](const char* field, bool has, double value, double& target) {
    if (!has) return;
    if (!(std::isfinite(value) && value > 0 && value < 1)) {
      errors.push_back({std::string("options.") + field, "must be in (0, 1)"});
    }
    target = value;
  };
  positive("xtol_rel", o.has_xtol_rel(), o.xtol_rel(), p.xtol_rel);
  positive("ftol_rel", o.has_ftol_rel(), o.ftol_rel(), p.ftol_rel);
  positive("constraint_tolerance", o.has_constraint_tolerance(), o.constraint_tolerance(),
           p.constraint_tolerance);

  if (errors.empty() && out) *out = std::move(p);
  return errors;
}

// --- the optimisation ---------------------------------------------------------------------

double bound_scale(double bound) { return bound != 0.0 ? std::abs(bound) : 1.0; }

// Scaled violation of constraint j at value c: > 0 when violated.
double violation(const ConstraintSpec& c, double value) {
  double v = 0.0;
  if (c.upper) v = std::max(v, (value - *c.upper) / bound_scale(*c.upper));
  if (c.lower) v = std::max(v, (*c.lower - value) / bound_scale(*c.lower));
  return v;
}

class Evaluator {
 public:
  Evaluator(const Problem& problem, const rel::ModelEvaluator& model, const OptimizeOptions& options)
      : p_(problem), model_(model), options_(options), start_(std::chrono::steady_clock::now()) {}

  // The evaluation at x (cached: NLopt asks for the objective and each constraint separately).
  const Evaluation& at(const std::vector<double>& x) {
    for (auto it = history_.rbegin(); it != history_.rend(); ++it) {
      if (it->x == x) return *it;
    }
    const std::size_t n = x.size();
    std::vector<FunctionalValue> values;
    if (!p_.functionals.empty()) {
      values = model_.evaluate(p_.names, x, p_.functionals, true).values;
    }
    // A value and its gradient; a non-finite one stops the run naming it and the point (the
    // optimiser would otherwise step to NaN and fail on the model instead).
    const auto quantity = [&](const Quantity& q, std::vector<double>& gradient, const std::string& what) {
      gradient.assign(n, 0.0);
      double value;
      if (q.expression) {
        value = q.expression->evaluate(x, gradient);
      } else {
        const FunctionalValue& f = values.at(static_cast<std::size_t>(q.functional));
        gradient = f.gradient;
        value = f.value;
      }
      bool finite = std::isfinite(value);
      for (const double d : gradient) finite = finite && std::isfinite(d);
      if (!finite) {
        std::string at;
        for (std::size_t i = 0; i < n; ++i) at += (i ? ", " : "") + p_.names[i] + " = " + std::to_string(x[i]);
        throw std::runtime_error(what + " or its gradient is not finite at " + at);
      }
      return value;
    };
    Evaluation e;
    e.index = static_cast<int>(history_.size()) + 1;
    e.x = x;
    e.objective = quantity(p_.objective, e.objective_gradient, "the objective");
    for (const auto& c : p_.constraints) {
      std::vector<double> g;
      e.constraints.push_back(quantity(c.quantity, g, "constraint '" + c.name + "'"));
      e.constraint_gradients.push_back(std::move(g));
      e.max_violation = std::max(e.max_violation, violation(c, e.constraints.back()));
    }
    e.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
    history_.push_back(std::move(e));
    if (options_.progress) options_.progress(history_.back());
    return history_.back();
  }

  std::vector<Evaluation>& history() { return history_; }

 private:
  const Problem& p_;
  const rel::ModelEvaluator& model_;
  const OptimizeOptions& options_;
  std::chrono::steady_clock::time_point start_;
  std::vector<Evaluation> history_;
};

struct Context {
  const Problem* problem = nullptr;
  Evaluator* evaluator = nullptr;
  double f_scale = 1.0;
  std::exception_ptr error;
};

std::vector<double> to_x(const Problem& p, const std::vector<double>& z) {
  std::vector<double> x(z.size());
  for (std::size_t i = 0; i < z.size(); ++i) x[i] = p.lower[i] + z[i] * (p.upper[i] - p.lower[i]);
  return x;
}

double objective(const std::vector<double>& z, std::vector<double>& grad, void* data) {
  auto* ctx = static_cast<Context*>(data);
  try {
    const Problem& p = *ctx->problem;
    const Evaluation& e = ctx->evaluator->at(to_x(p, z));
    const double sign = p.maximize ? -1.0 : 1.0;
    for (std::size_t i = 0; i < grad.size(); ++i) {
      grad[i] = sign * e.objective_gradient[i] * (p.upper[i] - p.lower[i]) / ctx->f_scale;
    }
    return sign * e.objective / ctx->f_scale;
  } catch (...) {
    ctx->error = std::current_exception();
    throw nlopt::forced_stop();
  }
}

// The scaled constraints (upper, then lower, per constraint as they are given) in one call.
void constraints(unsigned m, double* result, unsigned n, const double* z, double* grad, void* data) {
  auto* ctx = static_cast<Context*>(data);
  try {
    const Problem& p = *ctx->problem;
    const Evaluation& e = ctx->evaluator->at(to_x(p, std::vector<double>(z, z + n)));
    unsigned k = 0;
    for (std::size_t j = 0; j < p.constraints.size(); ++j) {
      const ConstraintSpec& c = p.constraints[j];
      for (int side = 0; side < 2; ++side) {
        const std::optional<double>& bound = side == 0 ? c.upper : c.lower;
        if (!bound) continue;
        const double sign = side == 0 ? 1.0 : -1.0;
        const double s = bound_scale(*bound);
        result[k] = sign * (e.constraints[j] - *bound) / s;
        if (grad) {
          for (unsigned i = 0; i < n; ++i) {
            grad[k * n + i] =
                sign * e.constraint_gradients[j][i] * (p.upper[i] - p.lower[i]) / s;
          }
        }
        ++k;
      }
    }
    (void)m;
  } catch (...) {
    ctx->error = std::current_exception();
    throw nlopt::forced_stop();
  }
}

std::string result_name(nlopt::result r) {
  switch (r) {
    case nlopt::SUCCESS: return "SUCCESS";
    case nlopt::STOPVAL_REACHED: return "STOPVAL_REACHED";
    case nlopt::FTOL_REACHED: return "FTOL_REACHED";
    case nlopt::XTOL_REACHED: return "XTOL_REACHED";
    case nlopt::MAXEVAL_REACHED: return "MAXEVAL_REACHED";
    case nlopt::MAXTIME_REACHED: return "MAXTIME_REACHED";
    case nlopt::FAILURE: return "FAILURE";
    case nlopt::INVALID_ARGS: return "INVALID_ARGS";
    case nlopt::OUT_OF_MEMORY: return "OUT_OF_MEMORY";
    case nlopt::ROUNDOFF_LIMITED: return "ROUNDOFF_LIMITED";
    case nlopt::FORCED_STOP: return "FORCED_STOP";
    default: return "RESULT_" + std::to_string(static_cast<int>(r));
  }
}

}  // namespace

pfem::v1::OptimizationProblem parse_problem_json(std::string_view json) {
  pfem::v1::OptimizationProblem problem;
  google::protobuf::util::JsonParseOptions options;
  options.ignore_unknown_fields = false;
  const auto status = google::protobuf::util::JsonStringToMessage(
      google::protobuf::StringPiece(json.data(), json.size()), &problem, options);
  if (!status.ok())
    throw ProblemError(
        json_errors(json, *pfem::v1::OptimizationProblem::descriptor(), "problem", std::string(status.message())));
  return problem;
}

pfem::v1::OptimizationProblem read_problem_file(const std::filesystem::path& path) {
  std::ifstream in(path);
  if (!in) throw ProblemError({{path.string(), "cannot open the problem file"}});
  std::stringstream buffer;
  buffer << in.rdbuf();
  return parse_problem_json(buffer.str());
}

std::vector<FieldError> validate_problem(const pfem::v1::OptimizationProblem& message) {
  return check(message, nullptr);
}

Problem build_problem(const pfem::v1::OptimizationProblem& message) {
  Problem p;
  auto errors = check(message, &p);
  if (!errors.empty()) throw ProblemError(std::move(errors));
  return p;
}

OptimizeResult optimize(const Problem& problem, const rel::ModelEvaluator& evaluator,
                        const OptimizeOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  const std::size_t n = problem.names.size();
  Evaluator eval(problem, evaluator, options);
  OptimizeResult r;
  r.gradient_source = problem.functionals.empty() ? "exact (expression AD)" : evaluator.gradient_source();
  r.initial = eval.at(problem.initial);  // throws when the start cannot be evaluated

  Context ctx;
  ctx.problem = &problem;
  ctx.evaluator = &eval;
  ctx.f_scale = std::abs(r.initial.objective) > 0 ? std::abs(r.initial.objective) : 1.0;
  nlopt::opt opt(problem.algorithm == Algorithm::kSlsqp ? nlopt::LD_SLSQP : nlopt::LD_MMA,
                 static_cast<unsigned>(n));
  opt.set_lower_bounds(std::vector<double>(n, 0.0));
  opt.set_upper_bounds(std::vector<double>(n, 1.0));
  opt.set_min_objective(objective, &ctx);
  unsigned m = 0;
  for (const auto& c : problem.constraints) m += (c.upper ? 1u : 0u) + (c.lower ? 1u : 0u);
  if (m > 0) {
    opt.add_inequality_mconstraint(constraints, &ctx,
                                   std::vector<double>(m, problem.constraint_tolerance));
  }
  opt.set_maxeval(problem.max_evaluations);
  opt.set_xtol_rel(problem.xtol_rel);
  opt.set_ftol_rel(problem.ftol_rel);
  std::vector<double> z(n);
  for (std::size_t i = 0; i < n; ++i) {
    z[i] = (problem.initial[i] - problem.lower[i]) / (problem.upper[i] - problem.lower[i]);
  }
  double fmin = 0.0;
  nlopt::result code = nlopt::FAILURE;
  try {
    code = opt.optimize(z, fmin);
    r.message = "stopped: ";
  } catch (const nlopt::forced_stop&) {
    code = nlopt::FORCED_STOP;
  } catch (const nlopt::roundoff_limited&) {
    code = nlopt::ROUNDOFF_LIMITED;
  } catch (const std::exception& e) {
    code = nlopt::FAILURE;
    r.message = std::string("NLopt failed: ") + e.what();
  }
  r.nlopt_result = result_name(code);
  if (ctx.error) {
    try {
      std::rethrow_exception(ctx.error);
    } catch (const std::exception& e) {
      r.message = std::string("an evaluation failed: ") + e.what();
    }
  } else if (r.message.empty() || r.message == "stopped: ") {
    switch (code) {
      case nlopt::XTOL_REACHED: r.message = "the design moved less than xtol_rel"; break;
      case nlopt::FTOL_REACHED: r.message = "the objective changed less than ftol_rel"; break;
      case nlopt::SUCCESS: r.message = "NLopt reports success"; break;
      case nlopt::MAXEVAL_REACHED: r.message = "max_evaluations reached"; break;
      case nlopt::ROUNDOFF_LIMITED: r.message = "stopped by roundoff"; break;
      default: r.message = "NLopt stopped: " + r.nlopt_result; break;
    }
  }
  auto& history = eval.history();
  // The design NLopt returns (its evaluation is in the history unless the run was stopped);
  // if it is infeasible or missing, the best feasible design seen.
  const std::vector<double> x_final = to_x(problem, z);
  const Evaluation* best = nullptr;
  for (const auto& e : history) {
    if (e.x == x_final) best = &e;
  }
  const auto better = [&](const Evaluation& a, const Evaluation& b) {
    return problem.maximize ? a.objective > b.objective : a.objective < b.objective;
  };
  if (!best || best->max_violation > problem.constraint_tolerance) {
    const Evaluation* feasible = nullptr;
    for (const auto& e : history) {
      if (e.max_violation <= problem.constraint_tolerance && (!feasible || better(e, *feasible))) {
        feasible = &e;
      }
    }
    if (feasible) best = feasible;
  }
  if (!best) best = &history.back();
  r.best = *best;
  const bool tolerance_stop = code == nlopt::SUCCESS || code == nlopt::XTOL_REACHED ||
                              code == nlopt::FTOL_REACHED || code == nlopt::ROUNDOFF_LIMITED;
  r.converged = !ctx.error && tolerance_stop && r.best.max_violation <= problem.constraint_tolerance;
  r.history = history;
  r.simulations = evaluator.stats();
  r.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return r;
}

// --- reports ------------------------------------------------------------------------------

namespace {

std::string csv_number(double v) { return rel::JsonWriter::number(v); }

std::string seconds_text(double s) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.1f", s);
  return buf;
}

}  // namespace

std::string history_csv(const Problem& p, const OptimizeResult& r) {
  std::ostringstream out;
  out << "evaluation,seconds";
  for (const auto& n : p.names) out << "," << n;
  out << ",objective";
  for (const auto& c : p.constraints) out << "," << c.name;
  out << ",max_violation";
  for (const auto& n : p.names) out << ",dobjective/d" << n;
  for (const auto& c : p.constraints) {
    for (const auto& n : p.names) out << ",d" << c.name << "/d" << n;
  }
  out << "\n";
  for (const auto& e : r.history) {
    out << e.index << "," << csv_number(e.seconds);
    for (double v : e.x) out << "," << csv_number(v);
    out << "," << csv_number(e.objective);
    for (double v : e.constraints) out << "," << csv_number(v);
    out << "," << csv_number(e.max_violation);
    for (double v : e.objective_gradient) out << "," << csv_number(v);
    for (const auto& g : e.constraint_gradients) {
      for (double v : g) out << "," << csv_number(v);
    }
    out << "\n";
  }
  return out.str();
}

std::string result_json(const Problem& p, const OptimizeResult& r) {
  rel::JsonWriter w;
  w.begin_object();
  w.field("problem", p.name).field("description", p.description);
  w.field("algorithm", std::string(to_string(p.algorithm)));
  w.field("converged", r.converged).field("message", r.message).field("nlopt_result", r.nlopt_result);
  w.field("evaluations", static_cast<int>(r.history.size()));
  w.field("gradient_source", r.gradient_source);
  const auto named = [&](const std::string& key, const std::vector<double>& values) {
    w.key(key).begin_object();
    for (std::size_t i = 0; i < p.names.size() && i < values.size(); ++i) w.field(p.names[i], values[i]);
    w.end_object();
  };
  named("x", r.best.x);
  named("initial_x", r.initial.x);
  w.key("bounds").begin_object();
  for (std::size_t i = 0; i < p.names.size(); ++i) {
    w.key(p.names[i]).begin_object().field("lower", p.lower[i]).field("upper", p.upper[i]).end_object();
  }
  w.end_object();
  w.key("objective").begin_object();
  w.field("quantity", p.objective.text).field("maximize", p.maximize);
  w.field("value", r.best.objective).field("initial", r.initial.objective);
  w.end_object();
  named("objective_gradient", r.best.objective_gradient);
  w.key("constraints").begin_array();
  for (std::size_t j = 0; j < p.constraints.size(); ++j) {
    const auto& c = p.constraints[j];
    w.begin_object();
    w.field("name", c.name).field("quantity", c.quantity.text);
    w.field("value", r.best.constraints[j]).field("initial", r.initial.constraints[j]);
    if (c.upper) w.field("upper", *c.upper);
    if (c.lower) w.field("lower", *c.lower);
    const double v = r.best.constraints[j];
    const double tol = 10 * p.constraint_tolerance;
    const bool active = (c.upper && std::abs(v - *c.upper) <= tol * bound_scale(*c.upper)) ||
                        (c.lower && std::abs(v - *c.lower) <= tol * bound_scale(*c.lower));
    w.field("active", active);
    named("gradient", r.best.constraint_gradients[j]);
    w.end_object();
  }
  w.end_array();
  w.field("max_violation", r.best.max_violation);
  w.field("best_evaluation", r.best.index);
  w.key("simulations").begin_object();
  w.field("evaluations", r.simulations.evaluations);
  w.field("gradient_evaluations", r.simulations.gradient_evaluations);
  w.field("runs", r.simulations.simulations).field("cached", r.simulations.cached);
  w.field("seconds", r.simulations.seconds);
  w.end_object();
  w.field("wall_seconds", r.wall_seconds);
  w.end_object();
  return w.take();
}

std::string summary_text(const Problem& p, const OptimizeResult& r) {
  std::ostringstream out;
  char line[512];
  out << "pfem-optimize: " << (p.name.empty() ? "(unnamed problem)" : p.name) << " - "
      << p.names.size() << " design variables, " << p.constraints.size() << " constraints, "
      << to_string(p.algorithm) << " (gradients: " << r.gradient_source << ")\n";
  out << (r.converged ? "converged" : "NOT CONVERGED") << " after " << r.history.size()
      << " evaluations (" << r.simulations.simulations << " PFEM simulations, "
      << seconds_text(r.wall_seconds) << " s): " << r.message << " [" << r.nlopt_result << "]\n";
  std::snprintf(line, sizeof line, "  %-14s %14s %14s %14s %14s\n", "variable", "lower", "initial",
                "optimum", "upper");
  out << line;
  for (std::size_t i = 0; i < p.names.size(); ++i) {
    std::snprintf(line, sizeof line, "  %-14s %14.6g %14.6g %14.6g %14.6g\n", p.names[i].c_str(),
                  p.lower[i], r.initial.x[i], r.best.x[i], p.upper[i]);
    out << line;
  }
  std::snprintf(line, sizeof line, "  %-14s %14s %14.6g %14.6g   %s %s\n", "objective", "",
                r.initial.objective, r.best.objective, p.maximize ? "maximise" : "minimise",
                p.objective.text.c_str());
  out << line;
  for (std::size_t j = 0; j < p.constraints.size(); ++j) {
    const auto& c = p.constraints[j];
    std::string bounds;
    if (c.lower) bounds += ">= " + rel::JsonWriter::number(*c.lower);
    if (c.upper) bounds += std::string(bounds.empty() ? "" : ", ") + "<= " + rel::JsonWriter::number(*c.upper);
    std::snprintf(line, sizeof line, "  %-14s %14s %14.6g %14.6g   %s %s\n", c.name.c_str(), "",
                  r.initial.constraints[j], r.best.constraints[j], c.quantity.text.c_str(),
                  bounds.c_str());
    out << line;
  }
  return out.str();
}

}  // namespace pfem::optimize
