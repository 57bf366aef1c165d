// Reliability-problem files: JSON -> proto -> domain, with one exact message per error that
// names the field path; and the example files build.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "clients/reliability/problem_io.h"

namespace rel = pfem::reliability;

namespace {

// Every error of a problem given as JSON, one string each (parse errors included).
std::vector<std::string> errors_of(const std::string& json) {
  std::vector<std::string> out;
  try {
    rel::build_problem(rel::parse_problem_json(json));
  } catch (const rel::ProblemError& e) {
    for (const auto& f : e.errors()) out.push_back(f.to_string());
  }
  return out;
}

std::string problem(const std::string& variables, const std::string& rest = "") {
  return R"({"name": "t", "variables": [)" + variables + "]" +
         (rest.empty() ? R"(, "limit_state": {"expression": "R - S"})" : rest) + "}";
}

const std::string kRS =
    R"({"name": "R", "distribution": "lognormal", "mean": 5, "stddev": 0.5},
       {"name": "S", "distribution": "gumbel", "mean": 2, "stddev": 0.6})";

using Errors = std::vector<std::string>;

}  // namespace

TEST(ReliabilityProblemIo, ValidProblemBuilds) {
  const rel::Problem p = rel::build_problem(rel::parse_problem_json(problem(
      kRS, R"(, "correlations": [{"a": "R", "b": "S", "rho": 0.3}],
              "limit_state": {"expression": "R - S"}, "method": "slsqp")")));
  EXPECT_EQ(p.names, (std::vector<std::string>{"R", "S"}));
  EXPECT_EQ(p.method, rel::FormMethod::kSlsqp);
  ASSERT_TRUE(p.transform.has_value());
  EXPECT_NE(p.transform->fictive_correlation()(0, 1), 0.3);  // solved, not copied
  EXPECT_NEAR(p.transform->fictive_correlation()(0, 1), 0.3, 0.02);
  const auto g = rel::make_limit_state(p);
  EXPECT_EQ(g->gradient_source(), "exact (expression AD)");
}

TEST(ReliabilityProblemIo, JsonErrorsNameTheField) {
  EXPECT_EQ(errors_of(problem(kRS + R"(, {"name": "U", "foo": 1})")),
            Errors{"variables[2].foo: unknown field of RandomVariable"});
  EXPECT_EQ(errors_of(R"({"nme": "x"})"), Errors{"nme: unknown field of ReliabilityProblem; did you mean 'name'?"});
  EXPECT_EQ(errors_of(problem(R"({"name": "R", "distribution": "normal", "mean": "abc"})")),
            Errors{"variables[0].mean: expected a number, found the string \"abc\""});
  EXPECT_EQ(errors_of(R"({"variables": {"name": "R", "mean": [5]}, "limit_state": "R - 1"})"),
            (Errors{"variables[0].mean: expected a number, found a list",
                    "limit_state: expected an object (LimitState), found the string \"R - 1\""}));
  EXPECT_EQ(errors_of(R"({"name": })"), Errors{"problem: invalid JSON at line 1, column 10: syntax error while "
                                               "parsing value - unexpected '}'; expected '[', '{', or a literal"});
}

TEST(ReliabilityProblemIo, VariableErrors) {
  EXPECT_EQ(errors_of(problem(R"({"name": "R", "distribution": "normal", "mean": 5, "stddev": 1},
                                 {"name": "S", "distribution": "normal", "mean": 2, "stddev": 0})")),
            Errors{"variables[1].stddev: must be > 0"});
  EXPECT_EQ(errors_of(problem(R"({"name": "R", "distribution": "lognorml", "mean": 5, "stddev": 1},
                                 {"name": "S", "distribution": "normal", "mean": 2, "stddev": 1})")),
            Errors{"variables[0].distribution: unknown distribution 'lognorml' (expected one of "
                   "normal, lognormal, uniform, gumbel, frechet, weibull, gamma, exponential, "
                   "beta, truncated_normal)"});
  EXPECT_EQ(errors_of(problem(R"({"name": "R", "distribution": "lognormal", "mean": 5, "stddev": 1, "lambda": 1},
                                 {"name": "S", "distribution": "normal", "mean": 2, "stddev": 1, "shape": 2})")),
            (Errors{"variables[0].lambda: give either mean and stddev or the native parameters "
                    "lambda and zeta of lognormal, not both",
                    "variables[1].shape: not a parameter of normal"}));
  EXPECT_EQ(errors_of(problem(R"({"name": "R", "distribution": "weibull", "scale": 5},
                                 {"name": "R", "distribution": "uniform", "lower": 3, "upper": 1})")),
            (Errors{"variables[0].shape: is required for weibull (or give mean and stddev)",
                    "variables[1].name: 'R' is already the name of variables[0]",
                    "variables[1].upper: must be > lower",
                    "limit_state.expression: column 5: unknown variable 'S'"}));
  EXPECT_EQ(errors_of(problem(R"({"name": "R", "distribution": "lognormal", "mean": -5, "stddev": 1},
                                 {"name": "S", "distribution": "beta", "mean": 2, "stddev": 1})")),
            (Errors{"variables[0].mean: must be > 0 for a lognormal variable",
                    "variables[1].lower: is required for beta",
                    "variables[1].upper: is required for beta"}));
}

TEST(ReliabilityProblemIo, CorrelationErrors) {
  EXPECT_EQ(errors_of(problem(kRS, R"(, "correlations": [{"a": "R", "b": "S", "rho": 1.0}],
                                     "limit_state": {"expression": "R - S"})")),
            Errors{"correlations[0].rho: must be in (-1, 1)"});
  EXPECT_EQ(errors_of(problem(kRS, R"(, "correlations": [{"a": "R", "b": "Q", "rho": 0.2},
                                                        {"a": "S", "b": "S", "rho": 0.2}],
                                     "limit_state": {"expression": "R - S"})")),
            (Errors{"correlations[0].b: unknown variable 'Q'", "correlations[1].b: must differ from a"}));
  const std::string three = R"({"name": "A", "distribution": "normal", "mean": 0, "stddev": 1},
                               {"name": "B", "distribution": "normal", "mean": 0, "stddev": 1},
                               {"name": "C", "distribution": "normal", "mean": 0, "stddev": 1})";
  EXPECT_EQ(errors_of(problem(three, R"(, "correlations": [{"a": "A", "b": "B", "rho": 0.9},
                                                          {"a": "B", "b": "C", "rho": 0.9},
                                                          {"a": "A", "b": "C", "rho": -0.9}],
                                       "limit_state": {"expression": "A + B + C"})")),
            Errors{"correlations: the correlation matrix is not positive definite"});
  const Errors unreachable = errors_of(problem(
      R"({"name": "R", "distribution": "lognormal", "mean": 1, "stddev": 2},
         {"name": "S", "distribution": "lognormal", "mean": 1, "stddev": 2})",
      R"(, "correlations": [{"a": "R", "b": "S", "rho": -0.9}], "limit_state": {"expression": "R - S"})"));
  ASSERT_EQ(unreachable.size(), 1u);
  EXPECT_EQ(unreachable[0].rfind("correlations[0].rho: this pair of distributions can only reach "
                                 "correlations in [",
                                 0),
            0u)
      << unreachable[0];
}

TEST(ReliabilityProblemIo, LimitStateAndMethodErrors) {
  EXPECT_EQ(errors_of(problem(kRS, R"j(, "limit_state": {"expression": "R - S * (1 + Q)"})j")),
            Errors{"limit_state.expression: column 14: unknown variable 'Q'"});
  EXPECT_EQ(errors_of(problem(kRS, R"(, "limit_state": {"expression": "R - S * (1 + R"})")),
            Errors{"limit_state.expression: column 9: '(' is never closed"});
  EXPECT_EQ(errors_of(problem(kRS, R"(, "method": "newton")")),
            (Errors{"limit_state: is required: {\"expression\": \"...\"} or {\"model\": {...}}",
                    "method: unknown method 'newton' (expected ihlrf, slsqp or cobyla)"}));
  EXPECT_EQ(errors_of(problem(kRS, R"(, "limit_state": {"model": {"model": {}, "recorder": "p",
              "functional": "mean", "threshold": 1, "parameters": {"Q": "rho"}}})")),
            (Errors{"limit_state.model.functional: unknown functional 'mean' (expected one of "
                    "at_time, max, min, max_abs, final)",
                    "limit_state.model.parameters[\"Q\"]: unknown variable 'Q'"}));
  EXPECT_EQ(errors_of(problem(kRS, R"(, "limit_state": {"model": {"model": {"analysis": {"t_end": 0.4}},
              "recorder": "p", "functional": "at_time", "time": 0.5, "threshold": 1}})")),
            Errors{"limit_state.model.time: must be in [0, 0.4] (the model's analysis.t_end)"});
}

// The model limit state itself (clients/reliability/model_limit_state.h) needs the engine or a
// server; this library alone validates the file and refuses to build it.
TEST(ReliabilityProblemIo, ModelLimitStateIsValidatedAndNeedsAnEvaluator) {
  const rel::Problem p = rel::build_problem(rel::parse_problem_json(problem(
      kRS, R"(, "limit_state": {"model": {"model": {"name": "m", "analysis": {"t_end": 1}}, "recorder": "p",
              "functional": "at_time", "time": 0.5, "threshold": 1, "parameters": {"R": "rho"}}})")));
  EXPECT_EQ(p.limit_state_kind, rel::LimitStateKind::kModel);
  EXPECT_THROW(rel::make_limit_state(p), rel::NotAvailableError);
}

TEST(ReliabilityProblemIo, ExampleFilesBuild) {
  for (const char* name : {"example.json", "nowak_collins_beam.json", "weibull_frechet.json",
                           "model_limit_state.json", "dam-break-obstacle.json"}) {
    SCOPED_TRACE(name);
    const auto message = rel::read_problem_file(std::string(PFEM_SOURCE_DIR) +
                                                "/examples/reliability/" + name);
    EXPECT_FALSE(message.description().empty());
    EXPECT_TRUE(rel::validate_problem(message).empty());
  }
  try {
    rel::read_problem_file("/nonexistent/problem.json");
    FAIL() << "expected an error";
  } catch (const rel::ProblemError& e) {
    EXPECT_EQ(std::string(e.what()), "/nonexistent/problem.json: cannot open the problem file");
  }
}
