// pfem-form importance sampling on a model limit state (examples/reliability/
// model_limit_state.json, about 0.05 s a simulation) against three pfem-server replicas on
// 127.0.0.1 behind one ipv4: target: the simulations are spread over all three (each server
// counts the runs of its engine), beta and pf are bit-identical to one server at concurrency
// 1, and with one replica killed by SIGKILL mid-run the analysis completes with the same result.
#include <unistd.h>

#include <atomic>
#include <cstdio>
#include <fstream>
#include <regex>
#include <sstream>

#include "tests/integration/server_process.h"
#include "tests/integration/service_test_support.h"

namespace {

using namespace pfem::testing;

const std::string kProblem =
    std::string(PFEM_SOURCE_DIR) + "/examples/reliability/model_limit_state.json";
constexpr const char* kSampling = " --importance-sampling 1000 --seed 3";

struct Output {
  int exit_code = -1;
  std::string out;
};

Output pfem_form(const std::string& args) {
  const std::string command = std::string(PFEM_BINARY_DIR) + "/bin/pfem-form " + kProblem +
                              kSampling + " " + args + " 2>&1";
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

// The text of a result.json field's value, as written (17 significant digits).
std::string field(const std::string& json, const std::string& pattern) {
  std::smatch m;
  if (!std::regex_search(json, m, std::regex(pattern + R"(\s*([^,}\n]+))"))) return "(missing)";
  return m[1];
}

struct Figures {
  std::string beta, pf, is_pf, is_cov, runs, retries;
};

Figures figures(const std::filesystem::path& dir) {
  const std::string json = slurp(dir / "result.json");
  return {field(json, R"("beta":)"), field(json, R"("pf":)"),
          field(json, R"("importance_sampling": \{[^}]*"pf":)"),
          field(json, R"("importance_sampling": \{[^}]*"cov":)"),
          field(json, R"("runs":)"), field(json, R"("retries":)")};
}

// One in-process replica whose engine counts its runs.
struct Replica {
  explicit Replica(const std::filesystem::path& dir) {
    auto o = local_options(dir);
    o.workers = 1;
    server = std::make_unique<pfem::server::Server>(
        o, [runs = runs](const pfem::v1::Model& m, const pfem::RunOptions& r) {
          ++*runs;
          return pfem::run(m, r);
        });
  }
  std::shared_ptr<std::atomic<int>> runs = std::make_shared<std::atomic<int>>(0);
  std::unique_ptr<pfem::server::Server> server;
};

std::vector<std::string> replica_flags(const std::filesystem::path& dir) {
  return {"--data-dir", dir.string(), "--workers", "1"};
}

// Wall time of the three-replica run of the first test: the second kills a replica at 40 % of it.
double three_replica_seconds = 2.0;

// The single-server reference, computed once.
const Figures& reference() {
  static const Figures f = [] {
    TempDir dir("replicas_ref");
    Replica one(dir.path / "data");
    const Output o = pfem_form("--out " + (dir.path / "out").string() + " --server " +
                               one.server->address() + " --concurrency 1");
    EXPECT_EQ(o.exit_code, 0) << o.out;
    return figures(dir.path / "out");
  }();
  return f;
}

}  // namespace

TEST(Replicas, ImportanceSamplingSpreadsOverThreeReplicasWithTheSameResult) {
  const Figures& ref = reference();
  ASSERT_NE(ref.is_pf, "(missing)");
  TempDir dir("replicas_spread");
  Replica a(dir.path / "a"), b(dir.path / "b"), c(dir.path / "c");
  const std::string target = "ipv4:" + a.server->address() + "," + b.server->address() + "," +
                             c.server->address();
  const auto start = std::chrono::steady_clock::now();
  const Output o = pfem_form("--out " + (dir.path / "out").string() + " --server " + target +
                             " --concurrency 3");
  three_replica_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  ASSERT_EQ(o.exit_code, 0) << o.out;
  const Figures f = figures(dir.path / "out");
  EXPECT_EQ(f.beta, ref.beta);
  EXPECT_EQ(f.pf, ref.pf);
  EXPECT_EQ(f.is_pf, ref.is_pf);
  EXPECT_EQ(f.is_cov, ref.is_cov);
  EXPECT_EQ(f.runs, ref.runs);
  const int runs[] = {*a.runs, *b.runs, *c.runs};
  std::printf("runs per replica: %d %d %d (of %s)\n", runs[0], runs[1], runs[2], f.runs.c_str());
  for (int r : runs) EXPECT_GT(r, 5);  // round_robin: every replica does a share
  EXPECT_EQ(runs[0] + runs[1] + runs[2], std::stoi(f.runs));
}

TEST(Replicas, ASigkilledReplicaCostsTimeNotTheResult) {
  const Figures& ref = reference();
  TempDir dir("replicas_kill");
  ServerProcess a(replica_flags(dir.path / "a")), b(replica_flags(dir.path / "b")),
      c(replica_flags(dir.path / "c"));
  const std::string target = "ipv4:" + a.address() + "," + b.address() + "," + c.address();
  std::atomic<bool> done{false};
  Output o;
  std::thread form([&] {
    o = pfem_form("--out " + (dir.path / "out").string() + " --server " + target +
                  " --concurrency 3");
    done = true;
  });
  // Mid-run: FORM is done and the sampling, three calls in flight, under way. b is frozen
  // first (SIGSTOP) so that the calls round_robin sends it meanwhile hang in its socket: when
  // SIGKILL comes, at least one call is in flight on it, however loaded the machine is.
  std::this_thread::sleep_for(std::chrono::duration<double>(0.4 * three_replica_seconds));
  ::kill(b.pid(), SIGSTOP);
  std::this_thread::sleep_for(std::chrono::milliseconds(500));
  const bool killed_mid_run = !done;
  b.stop(SIGKILL, 10);
  form.join();
  EXPECT_TRUE(killed_mid_run) << "the analysis ended before the kill: make it longer";
  ASSERT_EQ(o.exit_code, 0) << o.out;
  const Figures f = figures(dir.path / "out");
  EXPECT_EQ(f.beta, ref.beta);
  EXPECT_EQ(f.pf, ref.pf);
  EXPECT_EQ(f.is_pf, ref.is_pf);
  EXPECT_EQ(f.is_cov, ref.is_cov);
  std::printf("retries after the kill: %s\n", f.retries.c_str());
  EXPECT_GE(std::stoi(f.retries), 1) << o.out;  // the call in flight on the killed replica
}
