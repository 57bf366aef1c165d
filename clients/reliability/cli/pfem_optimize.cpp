// pfem-optimize: gradient-based design optimisation of a PFEM model (NLopt LD_SLSQP or LD_MMA)
// described by a problem file (proto3 JSON of pfem.v1.OptimizationProblem,
// proto/pfem/v1/optimization.proto).
//
//   pfem-optimize PROBLEM.json --out DIR [--server HOST:PORT [--token-file F]]
//                 [--gradients ddm|fdm] [--fdm-eps E] [--algorithm slsqp|mma]
//                 [--max-evaluations N] [--t-end T] [--threads N]
//
// Writes DIR/history.csv and DIR/result.json (clients/reliability/optimize.h), prints a summary on
// stdout and one line per evaluation on stderr.
// Exit codes: 0 converged; 1 ran but did not converge, or an evaluation failed; 2 bad command
// line or bad problem (one line per error, naming the field).
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <optional>
#include <string>
#include <vector>

#include "clients/cli/client.h"
#include "engine/cli/arguments.h"
#include "clients/reliability/optimize.h"

namespace opt = pfem::optimize;
namespace rel = pfem::reliability;

namespace {

constexpr const char* kUsage =
    "usage: pfem-optimize PROBLEM.json --out DIR [--server TARGET [--token-file F]]\n"
    "                     [--concurrency N] [--gradients ddm|fdm] [--fdm-eps E]\n"
    "                     [--algorithm slsqp|mma]\n"
    "                     [--max-evaluations N] [--t-end T] [--threads N]\n"
    "\n"
    "Minimises the problem's objective over its design variables (model parameters within\n"
    "bounds) subject to its constraints; objective and constraints are functionals of model\n"
    "recorders (at_time, max, min, max_abs, final) or expressions of the design variables.\n"
    "The model runs in-process, or through the gRPC Evaluate of pfem-server with --server:\n"
    "TARGET is HOST:PORT, dns:///NAME:PORT or ipv4:A:P,B:P (calls spread round_robin over the\n"
    "replicas, retried on another one when a replica is UNAVAILABLE).\n"
    "  --gradients ddm   exact gradients by direct differentiation, one run each (default)\n"
    "  --gradients fdm   central finite differences, 2P+1 runs per evaluation\n"
    "  --concurrency N   FDM: how many of the 2P+1 runs go at once (default 1)\n"
    "  --algorithm, --max-evaluations override the problem file's options\n"
    "  --t-end T         end time of the simulations (overrides the model's analysis.t_end)\n"
    "Writes DIR/history.csv (every evaluation: design, objective, constraints, gradients)\n"
    "and DIR/result.json. Exit codes: 0 converged, 1 not converged or failed, 2 bad input.\n";

[[noreturn]] void usage_error(const std::string& message) {
  std::cerr << "pfem-optimize: " << message << "\n" << kUsage;
  std::exit(2);
}

void print_errors(const std::vector<rel::FieldError>& errors) {
  for (const auto& e : errors) std::cerr << e.to_string() << "\n";
}

}  // namespace

int main(int argc, char** argv) {
  const std::vector<std::string> args(argv + 1, argv + argc);
  for (const auto& arg : args)
    if (arg == "-h" || arg == "--help") {
      std::cout << kUsage;
      return 0;
    }
  pfem::cli::Arguments cli(args);
  std::string problem_file, out, server, token_file;
  std::optional<std::string> gradients, algorithm;
  std::optional<double> fdm_eps, t_end;
  std::optional<int> max_evaluations, threads, concurrency;
  try {
    out = cli.take_string("--out").value_or("");
    server = cli.take_string("--server").value_or("");
    token_file = cli.take_string("--token-file").value_or("");
    gradients = cli.take_string("--gradients");
    fdm_eps = cli.take_double("--fdm-eps");
    algorithm = cli.take_string("--algorithm");
    max_evaluations = cli.take_int("--max-evaluations");
    t_end = cli.take_double("--t-end");
    threads = cli.take_int("--threads");
    concurrency = cli.take_int("--concurrency");
    cli.expect_done(1);
    problem_file = cli.positional(0);
  } catch (const std::invalid_argument& e) {
    usage_error(e.what());
  }
  if (out.empty()) usage_error("--out DIR is required");
  if (!token_file.empty() && server.empty()) usage_error("--token-file needs --server");

  try {
    opt::Problem problem = opt::build_problem(opt::read_problem_file(problem_file));
    std::vector<rel::FieldError> errors;
    rel::EvaluatorOptions eo;
    eo.server = server;
    if (gradients) {
      if (const auto g = rel::parse_gradient_method(*gradients)) {
        eo.gradients = *g;
      } else {
        errors.push_back({"--gradients", "unknown method '" + *gradients + "' (expected ddm or fdm)"});
      }
    }
    if (fdm_eps) {
      if (*fdm_eps > 0 && *fdm_eps < 0.1) eo.fdm_eps = *fdm_eps;
      else errors.push_back({"--fdm-eps", "must be in (0, 0.1)"});
    }
    if (t_end) {
      if (*t_end > 0) eo.t_end = *t_end;
      else errors.push_back({"--t-end", "must be > 0"});
    }
    if (concurrency) {
      if (*concurrency >= 1) eo.concurrency = *concurrency;
      else errors.push_back({"--concurrency", "must be >= 1"});
    }
    if (threads) {
      if (*threads >= 1) eo.threads = *threads;
      else errors.push_back({"--threads", "must be >= 1"});
    }
    if (algorithm) {
      if (const auto a = opt::parse_algorithm(*algorithm)) problem.algorithm = *a;
      else errors.push_back({"--algorithm", "unknown algorithm '" + *algorithm + "' (expected slsqp or mma)"});
    }
    if (max_evaluations) {
      if (*max_evaluations > 0) problem.max_evaluations = *max_evaluations;
      else errors.push_back({"--max-evaluations", "must be > 0"});
    }
    if (!token_file.empty()) {
      try {
        eo.token = pfem::client::read_token_file(token_file);
      } catch (const std::exception& e) {
        errors.push_back({"", e.what()});
      }
    }
    if (!errors.empty()) {
      print_errors(errors);
      return 2;
    }
    const auto evaluator = rel::make_evaluator(problem.model, eo, "model");
    opt::OptimizeOptions options;
    const std::size_t n = problem.names.size();
    options.progress = [&](const opt::Evaluation& e) {
      std::fprintf(stderr, "  evaluation %3d  %7.1f s  x =", e.index, e.seconds);
      for (std::size_t i = 0; i < n; ++i) std::fprintf(stderr, " %.6g", e.x[i]);
      std::fprintf(stderr, "  objective %.6g", e.objective);
      for (std::size_t j = 0; j < e.constraints.size(); ++j) {
        std::fprintf(stderr, "  %s %.6g", problem.constraints[j].name.c_str(), e.constraints[j]);
      }
      std::fprintf(stderr, "\n");
    };
    const opt::OptimizeResult result = opt::optimize(problem, *evaluator, options);

    std::error_code ec;
    std::filesystem::create_directories(out, ec);
    const auto dir = std::filesystem::path(out);
    for (const auto& [name, text] : {std::pair{"history.csv", opt::history_csv(problem, result)},
                                     std::pair{"result.json", opt::result_json(problem, result)}}) {
      std::ofstream file(dir / name);
      if (!(file << text)) {
        std::cerr << "pfem-optimize: cannot write " << (dir / name).string() << "\n";
        return 1;
      }
    }
    std::cout << opt::summary_text(problem, result);
    std::cout << "\nwrote " << (dir / "history.csv").string() << " and "
              << (dir / "result.json").string() << "\n";
    return result.converged ? 0 : 1;
  } catch (const rel::ProblemError& e) {
    print_errors(e.errors());
    return 2;
  } catch (const rel::ModelEvaluationError& e) {
    std::cerr << "pfem-optimize: " << e.what() << "\n";
    return 1;
  } catch (const std::exception& e) {
    std::cerr << "pfem-optimize: " << e.what() << "\n";
    return 1;
  }
}
