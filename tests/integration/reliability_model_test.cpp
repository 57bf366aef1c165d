// Model limit states (clients/reliability/model_limit_state.h) on a tiny soft cantilever
// holding back still water (20 particles, 20 steps, a few hundredths of a second a run):
// the DDM gradient of g against central differences of g, the same values through a
// pfem-server on 127.0.0.1, FDM gradients and their simulation count, FORM converging
// (improved HL-RF and SLSQP agreeing), and errors.
#include "tests/integration/service_test_support.h"

#include <cmath>

#include "clients/reliability/analysis.h"
#include "clients/reliability/model_limit_state.h"
#include "clients/reliability/problem_io.h"

namespace {

namespace rel = pfem::reliability;
using namespace pfem::testing;

// kTinyCantileverJson: the tip deflection peaks at 1.30 mm near t = 0.038 s (E = 1 MPa,
// rho = 1000). E lognormal (CoV 10 %), the water density normal (5 %, mapped to the model's "density");
// failure when the peak tip deflection exceeds 1.6 mm.
std::string problem_json(const std::string& limit_state_extra = "",
                         const std::string& threshold = "0.0016") {
  return std::string(R"({"name": "tiny", "variables": [
      {"name": "E", "distribution": "lognormal", "mean": 1e6, "stddev": 1e5},
      {"name": "rho", "distribution": "normal", "mean": 1000, "stddev": 50}],
    "limit_state": {"model": {"model": )") +
         kTinyCantileverJson + R"(, "recorder": "tip_ux", "functional": "max_abs", "threshold": )" +
         threshold + R"(, "parameters": {"rho": "density"})" + limit_state_extra + "}}}";
}

rel::Problem tiny_problem() {
  return rel::build_problem(rel::parse_problem_json(problem_json()));
}

void replace_once(std::string& text, const std::string& from, const std::string& to) {
  const auto at = text.find(from);
  ASSERT_NE(at, std::string::npos) << from;
  text.replace(at, from.size(), to);
}

std::unique_ptr<rel::LimitState> limit_state(const rel::Problem& p, rel::EvaluatorOptions o = {}) {
  return rel::make_limit_state(p, o);
}

TEST(ReliabilityModel, DdmGradientOfGMatchesCentralDifferences) {
  const rel::Problem p = tiny_problem();
  const auto g = limit_state(p);
  EXPECT_EQ(g->gradient_source(), "DDM, in-process");
  const std::vector<double> x = {1.1e6, 1020.0};
  std::vector<double> grad(2);
  const double g0 = g->evaluate(x, grad);
  EXPECT_NEAR(g0, 0.0016 - 0.00125, 2e-4);  // the peak drops a little for a stiffer wall
  EXPECT_GT(grad[0], 0.0);  // a stiffer wall deflects less: g = threshold - peak grows with E
  EXPECT_LT(grad[1], 0.0);  // heavier water pushes harder
  for (int i = 0; i < 2; ++i) {
    const double h = 1e-6 * x[i];
    std::vector<double> xp = x, xm = x;
    xp[i] += h;
    xm[i] -= h;
    const double fd = (g->evaluate(xp, {}) - g->evaluate(xm, {})) / (2 * h);
    SCOPED_TRACE(i);
    EXPECT_NEAR(grad[i], fd, 1e-5 * std::abs(fd) + 1e-14);
  }
  const auto stats = *g->simulation_stats();
  EXPECT_EQ(stats.evaluations, 5);
  EXPECT_EQ(stats.gradient_evaluations, 1);
  EXPECT_EQ(stats.simulations, 5);
}

TEST(ReliabilityModel, ServerGivesTheSameValuesAndGradients) {
  const rel::Problem p = tiny_problem();
  TempDir dir("reliability_model");
  pfem::server::Server server(local_options(dir.path));
  rel::EvaluatorOptions remote;
  remote.server = server.address();
  const auto local = limit_state(p);
  const auto via_server = limit_state(p, remote);
  EXPECT_EQ(via_server->gradient_source(), "DDM, server " + server.address());
  for (const std::vector<double>& x : {std::vector<double>{1e6, 1000.0}, {0.9e6, 1040.0}}) {
    std::vector<double> a(2), b(2);
    const double ga = local->evaluate(x, a);
    const double gb = via_server->evaluate(x, b);
    EXPECT_EQ(ga, gb);  // the same engine and functional code: bit-identical
    EXPECT_EQ(a, b);
  }
  // A repeated point is answered from the server's cache: no new simulation.
  std::vector<double> c(2);
  via_server->evaluate(std::vector<double>{1e6, 1000.0}, c);
  const auto stats = *via_server->simulation_stats();
  EXPECT_EQ(stats.evaluations, 3);
  EXPECT_EQ(stats.cached, 1);
  EXPECT_EQ(stats.simulations, 2);
}

TEST(ReliabilityModel, FdmGradientsAgreeAndCost2PPlus1Runs) {
  const rel::Problem p = tiny_problem();
  rel::EvaluatorOptions fdm;
  fdm.gradients = rel::GradientMethod::kFdm;
  fdm.fdm_eps = 1e-6;
  const auto g_fdm = limit_state(p, fdm);
  const auto g_ddm = limit_state(p);
  EXPECT_EQ(g_fdm->gradient_source(), "FDM (central, 2P+1 runs, eps 1e-06), in-process");
  const std::vector<double> x = {1e6, 1000.0};
  std::vector<double> a(2), b(2);
  EXPECT_EQ(g_fdm->evaluate(x, a), g_ddm->evaluate(x, b));
  for (int i = 0; i < 2; ++i) EXPECT_NEAR(a[i], b[i], 1e-5 * std::abs(b[i]));
  EXPECT_EQ(g_fdm->simulation_stats()->simulations, 5);  // 2 P + 1, P = 2
  g_fdm->evaluate(x, {});
  EXPECT_EQ(g_fdm->simulation_stats()->simulations, 6);  // values alone: one run
}

TEST(ReliabilityModel, FormConvergesAndMethodsAgree) {
  const rel::Problem p = tiny_problem();
  const auto g = limit_state(p);
  rel::AnalysisOptions o = rel::analysis_options(p);
  o.form.tolerance = 1e-6;
  const rel::AnalysisResult ihlrf = rel::analyze(p, *g, o);
  ASSERT_TRUE(ihlrf.form.converged) << ihlrf.form.message;
  o.form.method = rel::FormMethod::kSlsqp;
  const rel::AnalysisResult slsqp = rel::analyze(p, *g, o);
  ASSERT_TRUE(slsqp.form.converged) << slsqp.form.message;
  std::printf("beta %.6f (ihlrf, %d evaluations), %.6f (slsqp, %d); x* = (%.6g, %.6g)\n",
              ihlrf.form.beta, ihlrf.form.evaluations, slsqp.form.beta, slsqp.form.evaluations,
              ihlrf.form.x(0), ihlrf.form.x(1));
  // About (1.6 - 1.30) mm over a standard deviation of about 0.15 mm.
  EXPECT_GT(ihlrf.form.beta, 1.0);
  EXPECT_LT(ihlrf.form.beta, 4.0);
  EXPECT_NEAR(slsqp.form.beta, ihlrf.form.beta, 1e-4 * ihlrf.form.beta);
  // The design point is on g = 0: a softer wall and heavier water.
  EXPECT_LT(ihlrf.form.x(0), 1e6);
  EXPECT_GT(ihlrf.form.x(1), 1000.0);
  std::vector<double> x = {ihlrf.form.x(0), ihlrf.form.x(1)};
  EXPECT_NEAR(g->evaluate(x, {}), 0.0, 1e-6 * 0.0016);
  ASSERT_TRUE(ihlrf.simulations.has_value());
  EXPECT_GE(ihlrf.simulations->simulations, ihlrf.form.evaluations);
}

TEST(ReliabilityModel, InvalidParameterValuesGiveTheEnginesMessage) {
  const rel::Problem p = tiny_problem();
  const auto g = limit_state(p);
  try {
    std::vector<double> grad(2);
    g->evaluate(std::vector<double>{-1e6, 1000.0}, grad);
    FAIL() << "expected LimitStateError";
  } catch (const rel::LimitStateError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("E = -1000000"), std::string::npos) << what;
    EXPECT_NE(what.find("must be > 0"), std::string::npos) << what;
  }
}

TEST(ReliabilityModel, BadModelLimitStatesNameTheField) {
  const auto errors_of = [](const std::string& json) {
    std::vector<std::string> out;
    try {
      rel::make_limit_state(rel::build_problem(rel::parse_problem_json(json)), {});
    } catch (const rel::ProblemError& e) {
      for (const auto& err : e.errors()) out.push_back(err.to_string());
    }
    return out;
  };
  // rho has no model parameter of its name when the mapping is missing; a recorder that is not
  // in the model.
  std::string json = problem_json();
  replace_once(json, R"("parameters": {"rho": "density"})", R"("parameters": {})");
  replace_once(json, R"("recorder": "tip_ux")", R"("recorder": "tip_uy")");
  EXPECT_EQ(errors_of(json),
            (std::vector<std::string>{
                "limit_state.model.recorder: unknown recorder 'tip_uy' (the model's recorders: "
                "tip_ux, base_p)",
                "variables[1].name: the model has no parameter 'rho' (map the variable to one in "
                "limit_state.model.parameters; the model's parameters: E, density)"}));
  // A mapping to an unknown parameter, and two variables on one parameter.
  json = problem_json();
  replace_once(json, R"("parameters": {"rho": "density"})", R"("parameters": {"rho": "E"})");
  EXPECT_EQ(errors_of(json), (std::vector<std::string>{
                                 "limit_state.model.parameters[\"rho\"]: model parameter 'E' is "
                                 "already set by variable 'E'"}));
  json = problem_json();
  replace_once(json, R"("parameters": {"rho": "density"})", R"("parameters": {"rho": "rho_f"})");
  EXPECT_EQ(errors_of(json), (std::vector<std::string>{
                                 "limit_state.model.parameters[\"rho\"]: unknown model parameter "
                                 "'rho_f' (the model's parameters: E, density)"}));
  // The model's own errors, under the model's path.
  json = problem_json();
  replace_once(json, R"("mu": 0.01)", R"("mu": -1.0)");
  EXPECT_EQ(errors_of(json), (std::vector<std::string>{"limit_state.model.model.fluid.mu: must be >= 0"}));
}

TEST(ReliabilityModel, UnreachableServerIsALimitStateError) {
  rel::EvaluatorOptions remote;
  remote.server = "127.0.0.1:1";
  remote.timeout_seconds = 5;
  EXPECT_THROW(rel::make_limit_state(tiny_problem(), remote), rel::LimitStateError);
}

}  // namespace
