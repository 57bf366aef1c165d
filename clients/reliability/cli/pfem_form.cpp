// pfem-form: FORM (and on request SORM, importance sampling, Monte Carlo, subset simulation)
// for a reliability problem file (proto3 JSON of pfem.v1.ReliabilityProblem).
//
//   pfem-form PROBLEM.json --out DIR [--method ihlrf|slsqp|cobyla] [--sorm]
//             [--importance-sampling N] [--monte-carlo N] [--subset-simulation N] [--seed S]
//             [--max-iterations N] [--tolerance T] [--server TARGET [--token-file F]]
//             [--concurrency N] [--gradients ddm|fdm] [--fdm-eps E] [--t-end T] [--threads N]
//
// Model limit states run the PFEM engine in-process, or through the Evaluate of pfem-server
// replicas behind one gRPC target (round_robin) when --server is given; gradients by DDM
// (default) or by central FDM (--gradients fdm, 2P+1 simulations per gradient for P
// variables), reported with the simulation count. --concurrency N: how many simulations run at
// once (samples, chains, FDM runs, SORM gradients); the results do not depend on it.
// Writes DIR/result.json (see clients/reliability/report.h), prints a summary on stdout and
// the iterations on stderr when stderr is a terminal.
// Exit codes: 0 converged; 1 ran but did not converge, or the limit state failed;
// 2 bad command line or bad problem (one line per error, naming the field).
#include <unistd.h>

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "clients/cli/client.h"
#include "clients/reliability/analysis.h"
#include "clients/reliability/model_limit_state.h"
#include "clients/reliability/problem_io.h"
#include "clients/reliability/report.h"
#include "engine/cli/arguments.h"

namespace rel = pfem::reliability;

namespace {

constexpr const char* kUsage =
    "usage: pfem-form PROBLEM.json --out DIR [--method ihlrf|slsqp|cobyla] [--sorm]\n"
    "                 [--importance-sampling N] [--monte-carlo N] [--subset-simulation N]\n"
    "                 [--seed S] [--max-iterations N] [--tolerance T]\n"
    "                 [--server TARGET [--token-file F]] [--concurrency N]\n"
    "                 [--gradients ddm|fdm] [--fdm-eps E] [--t-end T] [--threads N]\n"
    "\n"
    "  --subset-simulation N   subset simulation (Au & Beck), N samples per level, p0 = 0.1\n"
    "  --concurrency N   evaluations of g at once: samples, chains, FDM runs, SORM gradients\n"
    "                    (the results for a seed do not depend on it)\n"
    "Model limit states (\"limit_state\": {\"model\": ...}) run the PFEM engine in-process, or\n"
    "through the gRPC Evaluate of pfem-server with --server (--token-file: bearer token).\n"
    "TARGET is any gRPC target: HOST:PORT, dns:///NAME:PORT or ipv4:A:P,B:P; calls are spread\n"
    "over its addresses (round_robin) and retried on another one when a replica is UNAVAILABLE.\n"
    "  --gradients ddm   exact gradients by direct differentiation, one run each (default)\n"
    "  --gradients fdm   central finite differences: 2P+1 value runs per gradient for P\n"
    "                    variables (relative step --fdm-eps, default 1e-7), run concurrently\n"
    "  --t-end T         end time of the simulations (overrides the model's analysis.t_end)\n"
    "  --threads N       in-process: threads of the element loops\n"
    "result.json reports the runs under \"simulations\".\n";

struct Args {
  std::string problem;
  std::string out;
  std::optional<std::string> method;
  bool sorm = false;
  std::optional<std::int64_t> importance_sampling;
  std::optional<std::int64_t> monte_carlo;
  std::optional<std::int64_t> subset_simulation;
  std::optional<int> concurrency;
  std::optional<std::uint64_t> seed;
  std::optional<int> max_iterations;
  std::optional<double> tolerance;
  std::string server;
  std::string token_file;
  std::optional<std::string> gradients;
  std::optional<double> fdm_eps;
  std::optional<double> t_end;
  std::optional<int> threads;
};

int usage_error(const std::string& message) {
  std::cerr << "pfem-form: " << message << "\n" << kUsage;
  return 2;
}

// Throws std::invalid_argument naming the flag at fault.
Args parse_args(pfem::cli::Arguments& cli) {
  Args a;
  a.out = cli.take_string("--out").value_or("");
  a.method = cli.take_string("--method");
  a.importance_sampling = cli.take_int64("--importance-sampling");
  a.monte_carlo = cli.take_int64("--monte-carlo");
  a.subset_simulation = cli.take_int64("--subset-simulation");
  a.concurrency = cli.take_int("--concurrency");
  a.seed = cli.take_uint64("--seed");
  a.max_iterations = cli.take_int("--max-iterations");
  a.tolerance = cli.take_double("--tolerance");
  a.server = cli.take_string("--server").value_or("");
  a.token_file = cli.take_string("--token-file").value_or("");
  a.gradients = cli.take_string("--gradients");
  a.fdm_eps = cli.take_double("--fdm-eps");
  a.t_end = cli.take_double("--t-end");
  a.threads = cli.take_int("--threads");
  a.sorm = cli.take_flag("--sorm");
  cli.expect_done(1);
  a.problem = cli.positional(0);
  if (a.out.empty()) throw std::invalid_argument("--out DIR is required");
  if (!a.token_file.empty() && a.server.empty()) {
    throw std::invalid_argument("--token-file needs --server");
  }
  return a;
}

void print_errors(const std::vector<rel::FieldError>& errors) {
  for (const auto& e : errors) std::cerr << e.to_string() << "\n";
}

}  // namespace

int main(int argc, char** argv) {
  pfem::cli::Arguments cli(std::vector<std::string>(argv + 1, argv + argc));
  if (cli.take_flag("--help") || cli.take_flag("-h")) {
    std::cout << kUsage;
    return 0;
  }
  Args args;
  try {
    args = parse_args(cli);
  } catch (const std::invalid_argument& e) {
    return usage_error(e.what());
  }
  try {
    const rel::Problem problem = rel::build_problem(rel::read_problem_file(args.problem));
    rel::AnalysisOptions options = rel::analysis_options(problem);
    std::vector<rel::FieldError> errors;
    if (args.method) {
      if (const auto m = rel::parse_form_method(*args.method)) {
        options.form.method = *m;
      } else {
        errors.push_back({"--method", "unknown method '" + *args.method +
                                          "' (expected ihlrf, slsqp or cobyla)"});
      }
    }
    if (args.sorm) options.sorm = true;
    if (args.importance_sampling) options.importance_sampling = *args.importance_sampling;
    if (args.monte_carlo) options.monte_carlo = *args.monte_carlo;
    if (args.subset_simulation) options.subset_simulation = *args.subset_simulation;
    if (args.concurrency) options.concurrency = *args.concurrency;
    if (args.seed) options.seed = *args.seed;
    if (args.max_iterations) options.form.max_iterations = *args.max_iterations;
    if (args.tolerance) options.form.tolerance = *args.tolerance;
    for (const auto& e : options.validate()) errors.push_back(e);
    rel::EvaluatorOptions evaluator;
    evaluator.server = args.server;
    evaluator.concurrency = std::max(1, options.concurrency);
    if (args.gradients) {
      if (const auto g = rel::parse_gradient_method(*args.gradients)) {
        evaluator.gradients = *g;
      } else {
        errors.push_back({"--gradients", "unknown method '" + *args.gradients + "' (expected ddm or fdm)"});
      }
    }
    if (args.fdm_eps) {
      if (*args.fdm_eps > 0 && *args.fdm_eps < 0.1) {
        evaluator.fdm_eps = *args.fdm_eps;
      } else {
        errors.push_back({"--fdm-eps", "must be in (0, 0.1)"});
      }
    }
    if (args.t_end) {
      if (*args.t_end > 0) {
        evaluator.t_end = *args.t_end;
      } else {
        errors.push_back({"--t-end", "must be > 0"});
      }
    }
    if (args.threads) {
      if (*args.threads >= 1) {
        evaluator.threads = *args.threads;
      } else {
        errors.push_back({"--threads", "must be >= 1"});
      }
    }
    const bool model = problem.limit_state_kind == rel::LimitStateKind::kModel;
    if (!model) {
      for (const auto& [flag, given] : {std::pair{"--server", !args.server.empty()},
                                        {"--gradients", args.gradients.has_value()},
                                        {"--fdm-eps", args.fdm_eps.has_value()},
                                        {"--t-end", args.t_end.has_value()}}) {
        if (given) errors.push_back({flag, "only used with a model limit state"});
      }
    }
    if (!args.token_file.empty()) {
      try {
        evaluator.token = pfem::client::read_token_file(args.token_file);
      } catch (const std::exception& e) {
        errors.push_back({"", e.what()});
      }
    }
    if (!errors.empty()) {
      print_errors(errors);
      return 2;
    }
    // Iterations on a terminal, and always for model limit states (each is a simulation).
    if (isatty(STDERR_FILENO) || problem.limit_state_kind == rel::LimitStateKind::kModel) {
      options.form.progress = [](const rel::FormIteration& it) {
        std::fprintf(stderr, "  iteration %3d  ||u|| = %-10.6g  G = %-12.5g  evaluations %d\n",
                     it.iteration, it.beta, it.g, it.evaluations);
      };
    }
    if (model) {
      std::fprintf(stderr, "pfem-form: model limit state, gradients by %s, simulations %s\n",
                   std::string(rel::to_string(evaluator.gradients)).c_str(),
                   args.server.empty() ? "in-process" : ("on " + args.server).c_str());
    }
    const std::unique_ptr<rel::LimitState> g = rel::make_limit_state(problem, evaluator);
    const rel::AnalysisResult result = rel::analyze(problem, *g, options);

    std::error_code ec;
    std::filesystem::create_directories(args.out, ec);
    const std::filesystem::path path = std::filesystem::path(args.out) / "result.json";
    std::ofstream file(path);
    if (!file) {
      std::cerr << "pfem-form: cannot write " << path.string() << "\n";
      return 1;
    }
    file << rel::result_json(problem, result, options);
    file.close();
    std::cout << rel::summary_text(problem, result, options);
    std::cout << "\nwrote " << path.string() << "\n";
    return result.form.converged ? 0 : 1;
  } catch (const rel::ProblemError& e) {
    print_errors(e.errors());
    return 2;
  } catch (const rel::NotAvailableError& e) {
    std::cerr << e.what() << "\n";
    return 2;
  } catch (const rel::LimitStateError& e) {
    std::cerr << "pfem-form: the limit state failed: " << e.what() << "\n";
    return 1;
  } catch (const std::exception& e) {
    std::cerr << "pfem-form: " << e.what() << "\n";
    return 1;
  }
}
