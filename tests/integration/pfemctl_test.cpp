// pfemctl against an in-process server: submit prints the id alone on the first line; watch
// exits 0 only on success; result writes the same files as `pfem run`; errors exit non-zero
// with the status name.
#include "tests/integration/service_test_support.h"

#include <sys/wait.h>

#include <cstdio>
#include <fstream>
#include <sstream>

#include "engine/io/results_io.h"

namespace {

using namespace pfem::testing;

struct Output {
  int exit_code = -1;
  std::string out;  // stdout and stderr together
};

Output run(const std::string& args) {
  const std::string command =
      std::string(PFEM_BINARY_DIR) + "/bin/pfemctl " + args + " 2>&1";
  Output o;
  FILE* pipe = ::popen(command.c_str(), "r");
  char buffer[4096];
  std::size_t n;
  while ((n = std::fread(buffer, 1, sizeof buffer, pipe)) > 0) o.out.append(buffer, n);
  const int status = ::pclose(pipe);
  o.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return o;
}

std::string slurp(const std::filesystem::path& file) {
  std::ifstream in(file);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

// A summary.json without its wall-time lines.
std::string without_timings(const std::string& summary) {
  std::istringstream in(summary);
  std::string kept, line;
  while (std::getline(in, line))
    if (line.find("_seconds\"") == std::string::npos) kept += line + "\n";
  return kept;
}

TEST(Pfemctl, EveryCommandAgainstALocalServer) {
  TempDir dir("pfemctl");
  const auto token_file = dir.path / "tokens";
  std::ofstream(token_file) << "ctl-token\n";
  auto options = local_options(dir.path / "data");
  options.token_file = token_file;
  pfem::server::Server server(options);
  const auto model_file = dir.path / "tiny.json";
  std::ofstream(model_file) << kTinyModelJson;
  const std::string base = "--server " + server.address() + " --token-file " + token_file.string();
  const std::string model = model_file.string();

  auto o = run(base + " validate " + model);
  EXPECT_EQ(o.exit_code, 0) << o.out;
  EXPECT_EQ(o.out, "valid: about 20 fluid particles, 5 steps\n");

  o = run(base + " submit " + model + " --sensitivity fdm --params rho_f --param rho_f=1010");
  ASSERT_EQ(o.exit_code, 0) << o.out;
  const std::string id = o.out.substr(0, o.out.find('\n'));
  ASSERT_EQ(id.size(), 16u) << o.out;

  o = run(base + " watch " + id);  // not a terminal: plain lines
  EXPECT_EQ(o.exit_code, 0) << o.out;
  EXPECT_NE(o.out.find("step 5/5"), std::string::npos) << o.out;
  EXPECT_NE(o.out.find(id + " SUCCEEDED\n"), std::string::npos) << o.out;

  const auto out_dir = dir.path / "out";
  o = run(base + " result " + id + " --out " + out_dir.string());
  EXPECT_EQ(o.exit_code, 0) << o.out;
  EXPECT_EQ(o.out, "wrote " + out_dir.string() +
                       ": 6 samples of 3 responses and 3 sensitivities (job SUCCEEDED)\n");
  // The files of `pfem run` on the same model and options, byte for byte (summary.json holds
  // wall times, so only its run-independent lines are compared).
  auto m = tiny_model();
  m.mutable_parameters(0)->set_value(1010.0);
  pfem::RunOptions run_options;
  run_options.sensitivity = pfem::SensitivityMethod::kFdm;
  run_options.params = {"rho_f"};
  const auto local_dir = dir.path / "local";
  pfem::write_results(pfem::run(m, run_options), local_dir);
  EXPECT_EQ(slurp(out_dir / "responses.csv"), slurp(local_dir / "responses.csv"));
  EXPECT_EQ(slurp(out_dir / "sensitivities.csv"), slurp(local_dir / "sensitivities.csv"));
  const std::string summary = slurp(out_dir / "summary.json");
  EXPECT_EQ(without_timings(summary), without_timings(slurp(local_dir / "summary.json")));
  EXPECT_NE(summary.find("\"steps\": 5,"), std::string::npos) << summary;
  EXPECT_NE(summary.find("\"factorizations\": 5,"), std::string::npos) << summary;
  EXPECT_NE(summary.find("\"parameters\": {\"rho_f\": 1010}"), std::string::npos) << summary;

  // DDM (Evaluate's default, here asked for explicitly): the sensitivity histories of every
  // recorder to every parameter of the model, the same files as `pfem run --sensitivity ddm`.
  o = run(base + " submit " + model + " --sensitivity ddm --param rho_f=1010");
  ASSERT_EQ(o.exit_code, 0) << o.out;
  const std::string ddm_id = o.out.substr(0, o.out.find('\n'));
  o = run(base + " watch " + ddm_id);
  EXPECT_EQ(o.exit_code, 0) << o.out;
  const auto ddm_dir = dir.path / "out_ddm";
  o = run(base + " result " + ddm_id + " --out " + ddm_dir.string());
  EXPECT_EQ(o.exit_code, 0) << o.out;
  EXPECT_EQ(o.out, "wrote " + ddm_dir.string() +
                       ": 6 samples of 3 responses and 6 sensitivities (job SUCCEEDED)\n");
  run_options.sensitivity = pfem::SensitivityMethod::kDdm;
  run_options.params.clear();
  const auto local_ddm = dir.path / "local_ddm";
  pfem::write_results(pfem::run(m, run_options), local_ddm);
  EXPECT_EQ(slurp(ddm_dir / "responses.csv"), slurp(local_ddm / "responses.csv"));
  EXPECT_EQ(slurp(ddm_dir / "sensitivities.csv"), slurp(local_ddm / "sensitivities.csv"));
  EXPECT_NE(slurp(ddm_dir / "summary.json").find("\"sensitivity_method\": \"ddm\""),
            std::string::npos);

  o = run(base + " list");
  EXPECT_EQ(o.exit_code, 0);
  EXPECT_NE(o.out.find(id + "  SUCCEEDED  tiny"), std::string::npos) << o.out;

  const std::string evaluate = base + " evaluate " + model +
                               " --sensitivity fdm --functional bottom_p:max"
                               " --functional front_x:at:0.004 --param rho_f=1010 --params rho_f";
  o = run(evaluate);
  EXPECT_EQ(o.exit_code, 0) << o.out;
  EXPECT_NE(o.out.find("d/drho_f"), std::string::npos) << o.out;
  EXPECT_NE(o.out.find("bottom_p:max"), std::string::npos) << o.out;
  EXPECT_NE(o.out.find("front_x:at:0.004"), std::string::npos) << o.out;
  EXPECT_EQ(o.out.find("(cached)"), std::string::npos) << o.out;
  const std::string first = o.out.substr(0, o.out.find("wall"));
  o = run(evaluate);
  EXPECT_NE(o.out.find("(cached)"), std::string::npos) << o.out;
  EXPECT_EQ(o.out.substr(0, o.out.find("wall")), first);  // the same numbers, printed alike

  o = run(base + " cancel " + id);
  EXPECT_EQ(o.exit_code, 1);
  EXPECT_NE(o.out.find("pfemctl: FAILED_PRECONDITION: job '" + id + "' has already finished"),
            std::string::npos)
      << o.out;

  o = run("--server " + server.address() + " list");  // no token
  EXPECT_EQ(o.exit_code, 1);
  EXPECT_EQ(o.out, "pfemctl: UNAUTHENTICATED: missing or invalid bearer token\n");

  o = run(base + " watch 0000000000000000");
  EXPECT_EQ(o.exit_code, 1);
  EXPECT_EQ(o.out, "pfemctl: NOT_FOUND: no job '0000000000000000'\n");

  o = run(base + " evaluate " + model + " --functional bottom_p:mean");
  EXPECT_EQ(o.exit_code, 2);
  EXPECT_NE(o.out.find("unknown kind 'mean'"), std::string::npos) << o.out;
}

}  // namespace
