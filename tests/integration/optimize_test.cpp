// pfem-optimize: the NLopt plumbing on a problem with a known optimum (expressions only, no
// simulation), the example problem (examples/optimize/cantilever-section.json, ~0.5 s per
// evaluation) converging through the real binary and through a pfem-server, and bad
// problem files giving one line per error naming the field (exit code 2).
#include "tests/integration/service_test_support.h"

#include <google/protobuf/struct.pb.h>
#include <google/protobuf/util/json_util.h>
#include <sys/wait.h>

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>

#include "clients/reliability/optimize.h"

namespace {

namespace fs = std::filesystem;
namespace opt = pfem::optimize;
namespace rel = pfem::reliability;
using namespace pfem::testing;

const std::string kExample =
    std::string(PFEM_SOURCE_DIR) + "/examples/optimize/cantilever-section.json";

std::string slurp(const fs::path& p) {
  std::ifstream in(p);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

struct CliRun {
  int exit_code;
  std::string out;
  std::string err;
};

CliRun pfem_optimize(const std::string& args, const fs::path& dir) {
  const std::string cmd = std::string(PFEM_BINARY_DIR) + "/bin/pfem-optimize " + args + " > " +
                          (dir / "stdout").string() + " 2> " + (dir / "stderr").string();
  const int status = std::system(cmd.c_str());
  return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, slurp(dir / "stdout"),
          slurp(dir / "stderr")};
}

// The example's model with an objective and constraints made of expressions only.
pfem::v1::OptimizationProblem expression_problem() {
  auto m = opt::read_problem_file(kExample);
  m.clear_constraints();
  m.mutable_objective()->mutable_quantity()->set_expression(
      "(width - 0.01)^2 + (depth - 0.02)^2");
  auto* c = m.add_constraints();
  c->set_name("sum");
  c->mutable_quantity()->set_expression("width + depth");
  c->set_upper(0.02);
  return m;
}

TEST(Optimize, KnownOptimumOfExpressionsWithoutSimulations) {
  // min (w - 0.01)^2 + (d - 0.02)^2 s.t. w + d <= 0.02, d <= 0.016: the projection of
  // (0.01, 0.02) on w + d = 0.02 is (0.005, 0.015), inside the bounds.
  const opt::Problem p = opt::build_problem(expression_problem());
  const auto evaluator = rel::make_evaluator(p.model, {});
  for (const auto algorithm : {opt::Algorithm::kSlsqp, opt::Algorithm::kMma}) {
    opt::Problem q = p;
    q.algorithm = algorithm;
    q.max_evaluations = 200;
    q.constraint_tolerance = 1e-6;
    q.xtol_rel = 1e-8;
    q.ftol_rel = 1e-12;
    // NLopt 2.7.1's MMA stalls from this infeasible start (w + d = 0.024): start it inside.
    if (algorithm == opt::Algorithm::kMma) q.initial = {0.0066, 0.008};
    const opt::OptimizeResult r = opt::optimize(q, *evaluator);
    SCOPED_TRACE(std::string(opt::to_string(algorithm)));
    EXPECT_TRUE(r.converged) << r.message;
    EXPECT_NEAR(r.best.x[0], 0.005, 2e-6);
    EXPECT_NEAR(r.best.x[1], 0.015, 2e-6);
    EXPECT_EQ(r.simulations.simulations, 0);
    EXPECT_EQ(r.gradient_source, "exact (expression AD)");
  }
}

// An objective that is not finite stops the run, naming it and the point (not NaN design
// variables handed to the model); at the start point it throws.
TEST(Optimize, ANonFiniteObjectiveStopsNamingIt) {
  auto m = expression_problem();
  m.mutable_objective()->mutable_quantity()->set_expression("width / 0");
  const opt::Problem p = opt::build_problem(m);
  const auto evaluator = rel::make_evaluator(p.model, {});
  try {
    opt::optimize(p, *evaluator);
    ADD_FAILURE() << "no error";
  } catch (const std::runtime_error& e) {
    EXPECT_STREQ(e.what(), "the objective or its gradient is not finite at width = 0.012000, depth = 0.012000");
  }
}

TEST(Optimize, ExampleConvergesThroughTheBinary) {
  TempDir dir("optimize_cli");
  const CliRun run = pfem_optimize(kExample + " --out " + dir.path.string(), dir.path);
  ASSERT_EQ(run.exit_code, 0) << run.out << run.err;
  EXPECT_NE(run.out.find("converged after"), std::string::npos) << run.out;
  google::protobuf::Struct r;
  ASSERT_TRUE(google::protobuf::util::JsonStringToMessage(slurp(dir.path / "result.json"), &r).ok());
  const auto& f = r.fields();
  EXPECT_TRUE(f.at("converged").bool_value());
  EXPECT_EQ(f.at("gradient_source").string_value(), "DDM, in-process");
  const auto& x = f.at("x").struct_value().fields();
  // The bending depth goes to its upper bound (I ~ width depth^3, area ~ width depth), the
  // width shrinks until the tip deflection reaches 1 mm: about 12 mm (0.75)^3 (1.37 mm) =
  // 6.9 mm (a little less: a narrower wall also weighs less).
  EXPECT_NEAR(x.at("depth").number_value(), 0.016, 1e-9);
  EXPECT_NEAR(x.at("width").number_value(), 0.0068, 0.0002);
  const auto& c = f.at("constraints").list_value().values(0).struct_value().fields();
  EXPECT_NEAR(c.at("value").number_value(), 0.001, 1e-6);
  EXPECT_TRUE(c.at("active").bool_value());
  const double objective = f.at("objective").struct_value().fields().at("value").number_value();
  EXPECT_NEAR(objective, x.at("width").number_value() * x.at("depth").number_value(), 1e-15);
  // history.csv: a header and one row per evaluation, gradients included.
  std::istringstream history(slurp(dir.path / "history.csv"));
  std::string header;
  std::getline(history, header);
  EXPECT_EQ(header,
            "evaluation,seconds,width,depth,objective,tip,max_violation,dobjective/dwidth,"
            "dobjective/ddepth,dtip/dwidth,dtip/ddepth");
  int rows = 0;
  for (std::string line; std::getline(history, line);) ++rows;
  EXPECT_EQ(rows, static_cast<int>(f.at("evaluations").number_value()));
  EXPECT_LE(rows, 15);
}

TEST(Optimize, ThroughTheServerTheSameDesign) {
  TempDir dir("optimize_server");
  pfem::server::Server server(local_options(dir.path));
  const opt::Problem p = opt::build_problem(opt::read_problem_file(kExample));
  rel::EvaluatorOptions remote;
  remote.server = server.address();
  const auto local = opt::optimize(p, *rel::make_evaluator(p.model, {}));
  const auto via_server = opt::optimize(p, *rel::make_evaluator(p.model, remote));
  ASSERT_TRUE(via_server.converged) << via_server.message;
  EXPECT_EQ(via_server.best.x, local.best.x);
  EXPECT_EQ(via_server.history.size(), local.history.size());
  EXPECT_EQ(via_server.gradient_source, "DDM, server " + server.address());
}

TEST(Optimize, BadProblemFilesNameTheFieldAndExitWith2) {
  TempDir dir("optimize_bad");
  auto m = opt::read_problem_file(kExample);
  m.mutable_variables(0)->clear_lower();
  m.mutable_variables(1)->set_name("height");
  m.mutable_objective()->mutable_quantity()->set_expression("width * (depth");
  m.mutable_constraints(0)->mutable_quantity()->set_recorder("tip_uy");
  m.mutable_constraints(0)->mutable_quantity()->set_functional("mean");
  m.mutable_constraints(0)->clear_upper();
  m.mutable_options()->set_algorithm("bfgs");
  m.mutable_model()->mutable_fluid()->set_rho(-1);
  std::string json;
  ASSERT_TRUE(google::protobuf::util::MessageToJsonString(m, &json).ok());
  std::ofstream(dir.path / "bad.json") << json;
  const CliRun run = pfem_optimize((dir.path / "bad.json").string() + " --out " +
                                       (dir.path / "out").string(),
                                   dir.path);
  EXPECT_EQ(run.exit_code, 2);
  EXPECT_EQ(run.err,
            "model.fluid.rho: must be > 0\n"
            "variables[0].lower: is required\n"
            "variables[1].name: the model has no parameter 'height' (the model's parameters: "
            "width, depth)\n"
            "objective.quantity.expression: column 10: unknown variable 'depth'\n"
            "constraints[0].quantity.functional: unknown functional 'mean' (expected one of "
            "at_time, max, min, max_abs, final)\n"
            "constraints[0]: give upper and/or lower (quantity <= upper, quantity >= lower)\n"
            "options.algorithm: unknown algorithm 'bfgs' (expected slsqp or mma)\n");
  EXPECT_FALSE(fs::exists(dir.path / "out" / "result.json"));

  // Unknown fields and JSON errors name the field; a missing file is named.
  std::ofstream(dir.path / "unknown.json") << R"({"name": "x", "variables": [{"name": "w", "lowr": 1}]})";
  const CliRun unknown = pfem_optimize((dir.path / "unknown.json").string() + " --out x", dir.path);
  EXPECT_EQ(unknown.exit_code, 2);
  EXPECT_EQ(unknown.err, "variables[0].lowr: unknown field of DesignVariable; did you mean 'lower'?\n");
  const CliRun missing = pfem_optimize("/nonexistent.json --out x", dir.path);
  EXPECT_EQ(missing.exit_code, 2);
  EXPECT_EQ(missing.err, "/nonexistent.json: cannot open the problem file\n");
  const CliRun flag = pfem_optimize(kExample + " --out x --gradients adjoint", dir.path);
  EXPECT_EQ(flag.exit_code, 2);
  EXPECT_EQ(flag.err, "--gradients: unknown method 'adjoint' (expected ddm or fdm)\n");
}

}  // namespace
