// End to end: the real `pfem-form` binary on the files in examples/reliability/, reading
// result.json back (as a google.protobuf.Struct) and checking the numbers and exit codes.
#include <gtest/gtest.h>

#include <google/protobuf/struct.pb.h>
#include <google/protobuf/util/json_util.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <utility>

namespace fs = std::filesystem;
using google::protobuf::Struct;
using google::protobuf::Value;

namespace {

struct CliRun {
  int exit_code;
  std::string out;
  std::string err;
};

std::string slurp(const fs::path& p) {
  std::ifstream in(p);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

CliRun pfem_form(const std::string& args, const fs::path& dir) {
  fs::create_directories(dir);
  const std::string cmd = std::string(PFEM_BINARY_DIR) + "/bin/pfem-form " + args + " > " +
                          (dir / "stdout").string() + " 2> " + (dir / "stderr").string();
  const int status = std::system(cmd.c_str());
  return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, slurp(dir / "stdout"),
          slurp(dir / "stderr")};
}

Struct read_result(const fs::path& dir) {
  Struct s;
  const auto status = google::protobuf::util::JsonStringToMessage(slurp(dir / "result.json"), &s);
  EXPECT_TRUE(status.ok()) << status.message();
  return s;
}

double number(const Struct& s, const std::string& key) { return s.fields().at(key).number_value(); }
const Struct& object(const Struct& s, const std::string& key) {
  return s.fields().at(key).struct_value();
}

std::string example(const std::string& name) {
  return std::string(PFEM_SOURCE_DIR) + "/examples/reliability/" + name;
}

fs::path scratch_root() {
  return fs::temp_directory_path() / ("pfem_form_test_" + std::to_string(::getpid()));
}

// Removes the scratch folders when the tests are done.
class ScratchCleanup : public ::testing::Environment {
 public:
  void TearDown() override { fs::remove_all(scratch_root()); }
};
const auto* const kCleanup = ::testing::AddGlobalTestEnvironment(new ScratchCleanup);

fs::path scratch(const std::string& name) {
  const fs::path dir = scratch_root() / name;
  fs::remove_all(dir);
  return dir;
}

}  // namespace

// Nowak & Collins (2000) Example 5.11 (published beta = 4.03; FORM to more digits 4.02211, as
// in the TesiproV package's test of the same example).
TEST(ReliabilityCli, NowakCollinsExampleWritesTheResult) {
  const fs::path dir = scratch("beam");
  const CliRun run = pfem_form(example("nowak_collins_beam.json") + " --out " + dir.string() +
                                " --importance-sampling 50000 --seed 3",
                            dir);
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const Struct r = read_result(dir);
  EXPECT_TRUE(r.fields().at("converged").bool_value());
  EXPECT_NEAR(number(r, "beta"), 4.03, 0.01);
  EXPECT_NEAR(number(r, "beta"), 4.02211455568222, 1e-6);
  EXPECT_NEAR(number(r, "pf"), 0.5 * std::erfc(number(r, "beta") / std::sqrt(2.0)), 1e-15);
  EXPECT_GT(number(r, "evaluations"), 0);
  EXPECT_EQ(r.fields().at("gradient_source").string_value(), "exact (expression AD)");
  const Struct& x = object(object(r, "design_point"), "x");
  EXPECT_NEAR(number(x, "Z") * number(x, "Fy") - number(x, "M"), 0.0, 1e-6 * number(x, "M"));
  const Struct& alpha = object(r, "alpha");
  EXPECT_LT(number(alpha, "Fy"), 0.0);  // capacity
  EXPECT_GT(number(alpha, "M"), 0.0);   // demand
  EXPECT_EQ(object(r, "sensitivities").fields().size(), 3u);
  // SORM (asked for in the file's options) and importance sampling (on the command line).
  const Struct& sorm = object(r, "sorm");
  const double pf_tvedt = number(object(sorm, "tvedt"), "pf");
  const Struct& is = object(r, "importance_sampling");
  EXPECT_NEAR(number(is, "pf"), pf_tvedt, 3 * number(is, "cov") * pf_tvedt);
  EXPECT_NE(run.out.find("beta = 4.02211"), std::string::npos) << run.out;
  EXPECT_NE(run.out.find("wrote "), std::string::npos);
}

TEST(ReliabilityCli, MethodsAgreeOnTheIssueExample) {
  double betas[3];
  const char* methods[3] = {"ihlrf", "slsqp", "cobyla"};
  for (int i = 0; i < 3; ++i) {
    const fs::path dir = scratch(std::string("example_") + methods[i]);
    const CliRun run = pfem_form(example("example.json") + " --out " + dir.string() + " --method " +
                                  methods[i],
                              dir);
    ASSERT_EQ(run.exit_code, 0) << run.err;
    const Struct r = read_result(dir);
    EXPECT_EQ(r.fields().at("method").string_value(), methods[i]);
    betas[i] = number(r, "beta");
  }
  EXPECT_NEAR(betas[1], betas[0], 1e-6);
  EXPECT_NEAR(betas[2], betas[0], 1e-5);
}

TEST(ReliabilityCli, ModelLimitStateConvergesWithDdmAndFdm) {
  // examples/reliability/model_limit_state.json: a tiny PFEM model (about 0.05 s a run).
  double betas[2];
  long long runs[2];
  const char* flags[] = {"", " --gradients fdm"};
  for (int i = 0; i < 2; ++i) {
    const fs::path dir = scratch(i == 0 ? "model_ddm" : "model_fdm");
    const CliRun run = pfem_form(example("model_limit_state.json") + " --out " + dir.string() +
                                     flags[i],
                                 dir);
    ASSERT_EQ(run.exit_code, 0) << run.err;
    EXPECT_NE(run.out.find("model limit state g = 0.0016 - max_abs(tip_ux)"), std::string::npos)
        << run.out;
    const Struct r = read_result(dir);
    EXPECT_TRUE(r.fields().at("converged").bool_value());
    EXPECT_EQ(r.fields().at("gradient_source").string_value(),
              i == 0 ? "DDM, in-process" : "FDM (central, 2P+1 runs, eps 1e-07), in-process");
    betas[i] = number(r, "beta");
    const Struct& sims = object(r, "simulations");
    runs[i] = static_cast<long long>(number(sims, "runs"));
    // Every evaluation of the iHLRF carries a gradient: DDM one run each, FDM 2P + 1 = 5.
    EXPECT_EQ(runs[i], (i == 0 ? 1 : 5) * static_cast<long long>(number(r, "evaluations")));
  }
  EXPECT_NEAR(betas[0], 1.66976, 1e-3);  // the README's run; FDM gradients must agree
  EXPECT_NEAR(betas[1], betas[0], 1e-5);
}

// Subset simulation and SORM on the model limit state, in-process, at concurrency 1 and 2: the
// same numbers (samples keyed by index, chains in lock step), subset simulation within 3 of
// its c.o.v. of SORM's Hohenbichler-Rackwitz pf (0.0462 with beam riders, the water's surface
// meeting the cantilever between two nodes; 0.0427 before, with the volume correction; 0.0401 on
// the engine of commit 135902c; 0.0663 before, with p = 0 imposed on the free surface), and FDM
// gradients (2P + 1 concurrent runs).
TEST(ReliabilityCli, ModelLimitStateSubsetSimulationAtAnyConcurrency) {
  std::string pf[2], sorm[2];
  for (int c = 1; c <= 2; ++c) {
    const fs::path dir = scratch("model_subset_" + std::to_string(c));
    const CliRun run = pfem_form(example("model_limit_state.json") + " --out " + dir.string() +
                                     " --subset-simulation 200 --sorm --gradients fdm --concurrency " +
                                     std::to_string(c),
                                 dir);
    ASSERT_EQ(run.exit_code, 0) << run.err;
    const Struct r = read_result(dir);
    const Struct& sus = object(r, "subset_simulation");
    EXPECT_TRUE(sus.fields().at("converged").bool_value());
    const double hr = number(object(object(r, "sorm"), "hohenbichler_rackwitz"), "pf");
    EXPECT_NEAR(hr, 0.0462, 0.0005);
    EXPECT_NEAR(number(sus, "pf"), hr, 3 * number(sus, "cov") * hr);
    EXPECT_EQ(sus.fields().at("levels").list_value().values_size(), 2);  // pf ~ 0.04: one level
    // The subset_simulation block as written, every number with 17 digits.
    const std::string json = slurp(dir / "result.json");
    const auto from = json.find("\"subset_simulation\"");
    pf[c - 1] = json.substr(from, json.find("\"simulations\"") - from);
    sorm[c - 1] = std::to_string(number(r, "beta")) + " " + std::to_string(hr);
  }
  EXPECT_EQ(pf[0], pf[1]);
  EXPECT_EQ(sorm[0], sorm[1]);
}

TEST(ReliabilityCli, ModelLimitStateErrors) {
  const fs::path dir = scratch("model_errors");
  // No server listening: exit code 1 with gRPC's reason.
  CliRun run = pfem_form(example("model_limit_state.json") + " --out " + dir.string() +
                             " --server 127.0.0.1:1",
                         dir);
  EXPECT_EQ(run.exit_code, 1);
  EXPECT_NE(run.err.find("pfem-form: the limit state failed: server 127.0.0.1:1: UNAVAILABLE"),
            std::string::npos)
      << run.err;
  EXPECT_FALSE(fs::exists(dir / "result.json"));
  run = pfem_form(example("model_limit_state.json") + " --out " + dir.string() +
                      " --gradients adjoint --t-end -1",
                  dir);
  EXPECT_EQ(run.exit_code, 2);
  EXPECT_EQ(run.err,
            "--gradients: unknown method 'adjoint' (expected ddm or fdm)\n"
            "--t-end: must be > 0\n");
  run = pfem_form(example("example.json") + " --out " + dir.string() + " --server 127.0.0.1:1",
                  dir);
  EXPECT_EQ(run.exit_code, 2);
  EXPECT_EQ(run.err, "--server: only used with a model limit state\n");
}

TEST(ReliabilityCli, BadProblemGivesOneLinePerErrorAndExitCode2) {
  const fs::path dir = scratch("bad");
  fs::create_directories(dir);
  std::ofstream(dir / "bad.json") << R"j({"name": "bad", "variables": [
      {"name": "R", "distribution": "lognormal", "mean": 5, "stddev": 0.5},
      {"name": "S", "distribution": "gumbel", "mean": 2, "stddev": -1}],
    "correlations": [{"a": "R", "b": "S", "rho": 1.5}],
    "limit_state": {"expression": "R - S * (1 + U)"}})j";
  const CliRun run = pfem_form((dir / "bad.json").string() + " --out " + dir.string(), dir);
  EXPECT_EQ(run.exit_code, 2);
  EXPECT_EQ(run.err,
            "variables[1].stddev: must be > 0\n"
            "correlations[0].rho: must be in (-1, 1)\n"
            "limit_state.expression: column 14: unknown variable 'U'\n");
  const CliRun usage = pfem_form((dir / "bad.json").string(), dir);
  EXPECT_EQ(usage.exit_code, 2);
  EXPECT_EQ(usage.err.rfind("pfem-form: --out DIR is required", 0), 0u) << usage.err;
  const CliRun method = pfem_form(example("example.json") + " --out " + dir.string() +
                                   " --method newton", dir);
  EXPECT_EQ(method.exit_code, 2);
  EXPECT_EQ(method.err, "--method: unknown method 'newton' (expected ihlrf, slsqp or cobyla)\n");
}

// The command line goes through the shared parser (engine/cli/arguments.h): each mistake gets
// one line naming the flag, then the usage, and exit code 2; --help prints the usage alone.
TEST(ReliabilityCli, CommandLineErrorsNameTheFlagAndPrintTheUsage) {
  const fs::path dir = scratch("usage");
  const std::string problem = example("example.json");
  const std::string out = " --out " + dir.string();
  const std::pair<std::string, std::string> cases[] = {
      {"", "expected 1 file argument(s), got 0"},
      {problem + " other.json" + out,
       "expected 1 file argument(s), got 2: '" + problem + "' 'other.json'"},
      {problem + out + " --bogus", "unknown option --bogus"},
      {problem + out + " -x", "unknown option -x"},
      {problem + " --out", "--out needs a value"},
      {problem + out + " --sorm --sorm", "--sorm given more than once"},
      {problem + out + " --seed -3", "--seed: '-3' is not a non-negative integer"},
      {problem + out + " --monte-carlo 1e4", "--monte-carlo: '1e4' is not an integer"},
      {problem + out + " --tolerance small", "--tolerance: 'small' is not a number"},
      {problem + out + " --token-file token", "--token-file needs --server"},
  };
  for (const auto& [args, message] : cases) {
    const CliRun run = pfem_form(args, dir);
    EXPECT_EQ(run.exit_code, 2) << args;
    const std::string head = "pfem-form: " + message + "\nusage: pfem-form PROBLEM.json --out DIR";
    EXPECT_EQ(run.err.rfind(head, 0), 0u) << args << "\n" << run.err;
    EXPECT_EQ(run.out, "") << args;
  }
  EXPECT_FALSE(fs::exists(dir / "result.json"));
  const CliRun help = pfem_form("--help", dir);
  EXPECT_EQ(help.exit_code, 0);
  EXPECT_EQ(help.out.rfind("usage: pfem-form PROBLEM.json --out DIR", 0), 0u) << help.out;
  EXPECT_EQ(help.err, "");
}
