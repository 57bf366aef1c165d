#include "clients/reliability/problem_io.h"

#include <google/protobuf/util/json_util.h>

#include <cctype>
#include <cmath>
#include <fstream>
#include <map>
#include <set>
#include <sstream>

#include "engine/base/json_errors.h"

namespace pfem::reliability {

namespace {

using pfem::v1::RandomVariable;

bool is_identifier(const std::string& s) {
  if (s.empty() || !(std::isalpha(static_cast<unsigned char>(s[0])) || s[0] == '_')) return false;
  for (char c : s) {
    if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '_')) return false;
  }
  return true;
}

// The optional numeric fields of a RandomVariable, by name.
struct Field {
  const char* name;
  bool (RandomVariable::*has)() const;
  double (RandomVariable::*get)() const;
};
const Field kFields[] = {
    {"mean", &RandomVariable::has_mean, &RandomVariable::mean},
    {"stddev", &RandomVariable::has_stddev, &RandomVariable::stddev},
    {"lower", &RandomVariable::has_lower, &RandomVariable::lower},
    {"upper", &RandomVariable::has_upper, &RandomVariable::upper},
    {"lambda", &RandomVariable::has_lambda, &RandomVariable::lambda},
    {"zeta", &RandomVariable::has_zeta, &RandomVariable::zeta},
    {"location", &RandomVariable::has_location, &RandomVariable::location},
    {"scale", &RandomVariable::has_scale, &RandomVariable::scale},
    {"shape", &RandomVariable::has_shape, &RandomVariable::shape},
    {"rate", &RandomVariable::has_rate, &RandomVariable::rate},
    {"shape_a", &RandomVariable::has_shape_a, &RandomVariable::shape_a},
    {"shape_b", &RandomVariable::has_shape_b, &RandomVariable::shape_b},
};

struct Parameterisation {
  std::vector<std::string> native_required;
  std::vector<std::string> native_optional;
  std::vector<std::string> moment_extra;  // allowed beside mean and stddev
};

Parameterisation parameterisation(DistributionKind kind) {
  switch (kind) {
    case DistributionKind::kNormal: return {{}, {}, {}};
    case DistributionKind::kLognormal: return {{"lambda", "zeta"}, {}, {}};
    case DistributionKind::kUniform: return {{"lower", "upper"}, {}, {}};
    case DistributionKind::kGumbel: return {{"location", "scale"}, {}, {}};
    case DistributionKind::kFrechet: return {{"scale", "shape"}, {}, {}};
    case DistributionKind::kWeibull: return {{"scale", "shape"}, {}, {}};
    case DistributionKind::kGamma: return {{"shape", "scale"}, {}, {}};
    case DistributionKind::kExponential: return {{"rate"}, {"lower"}, {"lower"}};
    case DistributionKind::kBeta: return {{"lower", "upper", "shape_a", "shape_b"}, {}, {"lower", "upper"}};
    case DistributionKind::kTruncatedNormal:
      return {{"location", "scale"}, {"lower", "upper"}, {"lower", "upper"}};
  }
  return {};
}

std::string join(const std::vector<std::string>& items, const std::string& last_sep = " and ") {
  std::string out;
  for (std::size_t i = 0; i < items.size(); ++i) {
    if (i > 0) out += (i + 1 == items.size()) ? last_sep : ", ";
    out += items[i];
  }
  return out;
}

bool contains(const std::vector<std::string>& v, const std::string& s) {
  return std::find(v.begin(), v.end(), s) != v.end();
}

// Builds the marginal of one variable, or adds errors under `path`.
std::optional<Distribution> build_marginal(const RandomVariable& v, const std::string& path,
                                           std::vector<FieldError>& errors) {
  if (v.distribution().empty()) {
    errors.push_back({path + ".distribution", "is required (one of " + distribution_names() + ")"});
    return std::nullopt;
  }
  const auto kind = parse_distribution_kind(v.distribution());
  if (!kind) {
    errors.push_back({path + ".distribution", "unknown distribution '" + v.distribution() +
                                                  "' (expected one of " + distribution_names() + ")"});
    return std::nullopt;
  }
  const std::string kind_name(to_string(*kind));
  const Parameterisation p = parameterisation(*kind);
  std::map<std::string, double> given;
  for (const Field& f : kFields) {
    if ((v.*f.has)()) given[f.name] = (v.*f.get)();
  }
  const bool moments = given.count("mean") || given.count("stddev") ||
                       (*kind == DistributionKind::kNormal);
  std::vector<std::string> natives = p.native_required;
  natives.insert(natives.end(), p.native_optional.begin(), p.native_optional.end());
  const std::string native_text =
      natives.empty() ? "" : " or the native parameters " + join(p.native_required);
  const std::size_t before = errors.size();
  for (const auto& [name, value] : given) {
    const bool is_moment = name == "mean" || name == "stddev";
    if (!is_moment && !contains(natives, name) && !contains(p.moment_extra, name)) {
      errors.push_back({path + "." + name, "not a parameter of " + kind_name});
    } else if (moments && !is_moment && !contains(p.moment_extra, name)) {
      errors.push_back({path + "." + name, "give either mean and stddev" + native_text +
                                               " of " + kind_name + ", not both"});
    } else if (!std::isfinite(value)) {
      errors.push_back({path + "." + name, "must be finite"});
    }
  }
  if (moments) {
    const bool exponential = *kind == DistributionKind::kExponential;
    if (!given.count("mean")) errors.push_back({path + ".mean", "is required (give mean and stddev" + native_text + ")"});
    if (!given.count("stddev") && !exponential) {
      errors.push_back({path + ".stddev", "is required (give mean and stddev" + native_text + ")"});
    }
    if (exponential && given.count("stddev") && given.count("lower")) {
      errors.push_back({path + ".lower", "not used when mean and stddev are given (lower = mean - stddev)"});
    }
    if (*kind == DistributionKind::kBeta) {
      for (const char* b : {"lower", "upper"}) {
        if (!given.count(b)) errors.push_back({path + "." + b, "is required for beta"});
      }
    }
  } else {
    for (const auto& name : p.native_required) {
      if (!given.count(name)) {
        errors.push_back({path + "." + name,
                          "is required for " + kind_name + " (or give mean and stddev)"});
      }
    }
  }
  if (errors.size() != before) return std::nullopt;

  const auto get = [&](const char* name, double fallback) {
    const auto it = given.find(name);
    return it == given.end() ? fallback : it->second;
  };
  const double inf = std::numeric_limits<double>::infinity();
  try {
    if (moments) {
      const double mean = given.at("mean");
      double stddev = get("stddev", 0.0);
      if (*kind == DistributionKind::kExponential && !given.count("stddev")) {
        stddev = mean - get("lower", 0.0);
        if (!(stddev > 0)) throw std::invalid_argument("mean: must be > lower (default 0)");
      }
      const bool truncated = *kind == DistributionKind::kTruncatedNormal;
      return Distribution::from_moments(*kind, mean, stddev,
                                        get("lower", truncated ? -inf : 0.0),
                                        get("upper", truncated ? inf : 0.0));
    }
    switch (*kind) {
      case DistributionKind::kLognormal: return Distribution::lognormal(get("lambda", 0), get("zeta", 0));
      case DistributionKind::kUniform: return Distribution::uniform(get("lower", 0), get("upper", 0));
      case DistributionKind::kGumbel: return Distribution::gumbel(get("location", 0), get("scale", 0));
      case DistributionKind::kFrechet: return Distribution::frechet(get("scale", 0), get("shape", 0));
      case DistributionKind::kWeibull: return Distribution::weibull(get("scale", 0), get("shape", 0));
      case DistributionKind::kGamma: return Distribution::gamma(get("shape", 0), get("scale", 0));
      case DistributionKind::kExponential: return Distribution::exponential(get("rate", 0), get("lower", 0));
      case DistributionKind::kBeta:
        return Distribution::beta(get("shape_a", 0), get("shape_b", 0), get("lower", 0), get("upper", 0));
      case DistributionKind::kTruncatedNormal:
        return Distribution::truncated_normal(get("location", 0), get("scale", 0), get("lower", -inf),
                                              get("upper", inf));
      case DistributionKind::kNormal: break;
    }
  } catch (const std::invalid_argument& e) {
    const std::string what = e.what();
    const auto colon = what.find(": ");
    if (colon == std::string::npos) {
      errors.push_back({path, what});
    } else {
      errors.push_back({path + "." + what.substr(0, colon), what.substr(colon + 2)});
    }
  }
  return std::nullopt;
}

std::pair<int, int> pair_key(int i, int j) { return {std::min(i, j), std::max(i, j)}; }

const std::vector<std::string> kFunctionals = {"at_time", "max", "min", "max_abs", "final"};

// Checks the message; fills `out` when there are no errors.
std::vector<FieldError> check(const pfem::v1::ReliabilityProblem& msg, Problem* out) {
  std::vector<FieldError> errors;
  const int n = msg.variables_size();
  if (n == 0) errors.push_back({"variables", "at least one variable is required"});

  std::vector<std::string> names(n);
  std::vector<std::optional<Distribution>> marginals(n);
  std::map<std::string, int> index;
  for (int i = 0; i < n; ++i) {
    const RandomVariable& v = msg.variables(i);
    const std::string path = "variables[" + std::to_string(i) + "]";
    names[i] = v.name();
    if (v.name().empty()) {
      errors.push_back({path + ".name", "is required"});
    } else if (!is_identifier(v.name())) {
      errors.push_back({path + ".name", "'" + v.name() +
                                            "' is not a valid name (letters, digits and _, not starting with a digit)"});
    } else if (index.count(v.name())) {
      errors.push_back({path + ".name", "'" + v.name() + "' is already the name of variables[" +
                                            std::to_string(index[v.name()]) + "]"});
    } else {
      index[v.name()] = i;
    }
    marginals[i] = build_marginal(v, path, errors);
  }

  // Correlations.
  Eigen::MatrixXd R = Eigen::MatrixXd::Identity(n, n);
  std::map<std::pair<int, int>, int> pair_entry;
  bool pairs_ok = true;
  for (int k = 0; k < msg.correlations_size(); ++k) {
    const auto& c = msg.correlations(k);
    const std::string path = "correlations[" + std::to_string(k) + "]";
    auto lookup = [&](const char* field, const std::string& name) {
      if (name.empty()) {
        errors.push_back({path + "." + field, "is required (a variable name)"});
      } else if (!index.count(name)) {
        errors.push_back({path + "." + field, "unknown variable '" + name + "'"});
      } else {
        return index.at(name);
      }
      return -1;
    };
    const int ia = lookup("a", c.a());
    const int ib = lookup("b", c.b());
    bool ok = ia >= 0 && ib >= 0;
    if (ok && ia == ib) {
      errors.push_back({path + ".b", "must differ from a"});
      ok = false;
    }
    if (!(std::abs(c.rho()) < 1.0)) {
      errors.push_back({path + ".rho", "must be in (-1, 1)"});
      ok = false;
    }
    if (ok) {
      const auto key = pair_key(ia, ib);
      if (pair_entry.count(key)) {
        errors.push_back({path, "the pair (" + c.a() + ", " + c.b() + ") is already in correlations[" +
                                    std::to_string(pair_entry[key]) + "]"});
        ok = false;
      } else {
        pair_entry[key] = k;
        R(ia, ib) = R(ib, ia) = c.rho();
      }
    }
    pairs_ok = pairs_ok && ok;
  }

  // Limit state.
  LimitStateKind ls_kind = LimitStateKind::kExpression;
  switch (msg.limit_state().kind_case()) {
    case pfem::v1::LimitState::KIND_NOT_SET:
      errors.push_back({"limit_state", "is required: {\"expression\": \"...\"} or {\"model\": {...}}"});
      break;
    case pfem::v1::LimitState::kExpression: {
      const std::string& text = msg.limit_state().expression();
      if (text.find_first_not_of(" \t\r\n") == std::string::npos) {
        errors.push_back({"limit_state.expression", "is empty"});
      } else {
        try {
          Expression::parse(text, names);
        } catch (const ExpressionError& e) {
          errors.push_back({"limit_state.expression", e.what()});
        }
      }
      break;
    }
    case pfem::v1::LimitState::kModel: {
      ls_kind = LimitStateKind::kModel;
      const auto& m = msg.limit_state().model();
      const std::string path = "limit_state.model";
      if (!m.has_model()) errors.push_back({path + ".model", "is required (a pfem.v1.Model)"});
      if (m.recorder().empty()) errors.push_back({path + ".recorder", "is required"});
      if (m.functional().empty()) {
        errors.push_back({path + ".functional", "is required (one of " + join(kFunctionals, ", ") + ")"});
      } else if (!contains(kFunctionals, m.functional())) {
        errors.push_back({path + ".functional", "unknown functional '" + m.functional() +
                                                    "' (expected one of " + join(kFunctionals, ", ") + ")"});
      } else if (m.functional() == "at_time" && !m.has_time()) {
        errors.push_back({path + ".time", "is required for at_time"});
      } else if (m.functional() == "at_time" && m.has_model() &&
                 !(m.time() >= 0.0 && m.time() <= m.model().analysis().t_end())) {
        std::ostringstream why;
        why << "must be in [0, " << m.model().analysis().t_end() << "] (the model's analysis.t_end)";
        errors.push_back({path + ".time", why.str()});
      } else if (m.functional() != "at_time" && m.has_time()) {
        errors.push_back({path + ".time", "only used with at_time"});
      }
      std::set<std::string> keys;
      for (const auto& entry : m.parameters()) keys.insert(entry.first);
      for (const auto& key : keys) {
        if (!index.count(key)) {
          errors.push_back({path + ".parameters[\"" + key + "\"]", "unknown variable '" + key + "'"});
        } else if (m.parameters().at(key).empty()) {
          errors.push_back({path + ".parameters[\"" + key + "\"]", "is empty (a model parameter name)"});
        }
      }
      break;
    }
  }

  // Method and options.
  FormMethod method = FormMethod::kIhlrf;
  if (!msg.method().empty()) {
    if (const auto parsed = parse_form_method(msg.method())) {
      method = *parsed;
    } else {
      errors.push_back({"method", "unknown method '" + msg.method() + "' (expected ihlrf, slsqp or cobyla)"});
    }
  }
  const auto& o = msg.options();
  if (o.has_max_iterations() && o.max_iterations() <= 0) errors.push_back({"options.max_iterations", "must be > 0"});
  if (o.has_tolerance() && !(o.tolerance() > 0 && o.tolerance() < 1)) {
    errors.push_back({"options.tolerance", "must be in (0, 1)"});
  }
  if (o.importance_sampling() < 0) errors.push_back({"options.importance_sampling", "must be >= 0"});
  if (o.monte_carlo() < 0) errors.push_back({"options.monte_carlo", "must be >= 0"});
  if (o.subset_simulation() < 0) {
    errors.push_back({"options.subset_simulation", "must be >= 0"});
  } else if (o.subset_simulation() > 0 && o.subset_simulation() % 10 != 0) {
    errors.push_back({"options.subset_simulation", "must be a multiple of 10 (p0 = 0.1)"});
  }

  // The Nataf transformation, when everything it needs is valid.
  std::optional<NatafTransform> transform;
  const bool marginals_ok =
      std::all_of(marginals.begin(), marginals.end(), [](const auto& m) { return m.has_value(); });
  if (n > 0 && marginals_ok && pairs_ok) {
    std::vector<Distribution> dists;
    for (const auto& m : marginals) dists.push_back(*m);
    try {
      transform.emplace(std::move(dists), R);
    } catch (const NatafError& e) {
      if (e.i() >= 0) {
        const int k = pair_entry.at(pair_key(e.i(), e.j()));
        errors.push_back({"correlations[" + std::to_string(k) + "].rho",
                          std::string(e.what()) + " (" + names[e.i()] + " " +
                              std::string(to_string(marginals[e.i()]->kind())) + ", " + names[e.j()] + " " +
                              std::string(to_string(marginals[e.j()]->kind())) + ")"});
      } else {
        errors.push_back({"correlations", e.what()});
      }
    }
  }

  if (errors.empty() && out) {
    out->name = msg.name();
    out->description = msg.description();
    out->names = names;
    for (const auto& m : marginals) out->marginals.push_back(*m);
    out->transform = std::move(transform);
    out->limit_state_kind = ls_kind;
    out->expression = ls_kind == LimitStateKind::kExpression ? msg.limit_state().expression() : "";
    out->method = method;
    out->message = msg;
  }
  return errors;
}

}  // namespace

pfem::v1::ReliabilityProblem parse_problem_json(std::string_view json) {
  pfem::v1::ReliabilityProblem problem;
  google::protobuf::util::JsonParseOptions options;
  options.ignore_unknown_fields = false;
  const auto status = google::protobuf::util::JsonStringToMessage(
      google::protobuf::StringPiece(json.data(), json.size()), &problem, options);
  if (!status.ok())
    throw ProblemError(
        json_errors(json, *pfem::v1::ReliabilityProblem::descriptor(), "problem", std::string(status.message())));
  return problem;
}

pfem::v1::ReliabilityProblem read_problem_file(const std::filesystem::path& path) {
  std::ifstream in(path);
  if (!in) throw ProblemError({{path.string(), "cannot open the problem file"}});
  std::stringstream buffer;
  buffer << in.rdbuf();
  return parse_problem_json(buffer.str());
}

std::vector<FieldError> validate_problem(const pfem::v1::ReliabilityProblem& message) {
  return check(message, nullptr);
}

Problem build_problem(const pfem::v1::ReliabilityProblem& message) {
  Problem problem;
  auto errors = check(message, &problem);
  if (!errors.empty()) throw ProblemError(std::move(errors));
  return problem;
}

std::unique_ptr<LimitState> make_limit_state(const Problem& problem) {
  if (problem.limit_state_kind == LimitStateKind::kModel) {
    throw NotAvailableError(
        "limit_state.model: a model limit state needs a PFEM evaluator: use "
        "make_limit_state(problem, EvaluatorOptions) of clients/reliability/model_limit_state.h "
        "(library pfem_reliability_model)");
  }
  return std::make_unique<ExpressionLimitState>(problem.expression, problem.names);
}

}  // namespace pfem::reliability
