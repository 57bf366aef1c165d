// pfem-form: FORM (and on request SORM, importance sampling, Monte Carlo) for a reliability
// problem file (proto3 JSON of pfem.v1.ReliabilityProblem).
//
//   pfem-form PROBLEM.json --out DIR [--method ihlrf|slsqp|cobyla] [--sorm]
//             [--importance-sampling N] [--monte-carlo N] [--seed S] [--max-iterations N]
//             [--tolerance T] [--server HOST:PORT [--token-file F]] [--gradients ddm|fdm]
//             [--fdm-eps E] [--t-end T] [--threads N]
//
// Model limit states run the PFEM engine in-process, or through a pfem-server's Evaluate
// when --server is given; gradients by DDM (default) or by central FDM (--gradients fdm,
// 2P+1 simulations per gradient for P variables), reported with the simulation count.
// Writes DIR/result.json (see clients/reliability/report.h), prints a summary on stdout and
// the iterations on stderr when stderr is a terminal.
// Exit codes: 0 converged; 1 ran but did not converge, or the limit state failed;
// 2 bad command line or bad problem (one line per error, naming the field).
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <optional>
#include <string>
#include <vector>

#include "clients/cli/client.h"
#include "clients/reliability/analysis.h"
#include "clients/reliability/model_limit_state.h"
#include "clients/reliability/problem_io.h"
#include "clients/reliability/report.h"

namespace rel = pfem::reliability;

namespace {

constexpr const char* kUsage =
    "usage: pfem-form PROBLEM.json --out DIR [--method ihlrf|slsqp|cobyla] [--sorm]\n"
    "                 [--importance-sampling N] [--monte-carlo N] [--seed S]\n"
    "                 [--max-iterations N] [--tolerance T]\n"
    "                 [--server HOST:PORT [--token-file F]] [--gradients ddm|fdm]\n"
    "                 [--fdm-eps E] [--t-end T] [--threads N]\n"
    "\n"
    "Model limit states (\"limit_state\": {\"model\": ...}) run the PFEM engine in-process, or\n"
    "through the gRPC Evaluate of a pfem-server with --server (--token-file: bearer token).\n"
    "  --gradients ddm   exact gradients by direct differentiation, one run each (default)\n"
    "  --gradients fdm   central finite differences by the engine: 2P+1 runs per gradient\n"
    "                    for P variables (relative step --fdm-eps, default 1e-7)\n"
    "  --t-end T         end time of the simulations (overrides the model's analysis.t_end)\n"
    "  --threads N       in-process: threads of the element loops\n"
    "result.json reports the runs under \"simulations\".\n";

struct Args {
  std::string problem;
  std::string out;
  std::optional<std::string> method;
  bool sorm = false;
  std::optional<long long> importance_sampling;
  std::optional<long long> monte_carlo;
  std::optional<unsigned long long> seed;
  std::optional<int> max_iterations;
  std::optional<double> tolerance;
  std::string server;
  std::string token_file;
  std::optional<std::string> gradients;
  std::optional<double> fdm_eps;
  std::optional<double> t_end;
  std::optional<int> threads;
};

[[noreturn]] void usage_error(const std::string& message) {
  std::cerr << "pfem-form: " << message << "\n" << kUsage;
  std::exit(2);
}

template <class T>
T parse_number(const std::string& flag, const std::string& text) {
  try {
    std::size_t used = 0;
    T value;
    if constexpr (std::is_same_v<T, double>) {
      value = std::stod(text, &used);
    } else if constexpr (std::is_same_v<T, unsigned long long>) {
      if (!text.empty() && text[0] == '-') throw std::invalid_argument("negative");
      value = std::stoull(text, &used);
    } else {
      value = static_cast<T>(std::stoll(text, &used));
    }
    if (used != text.size()) throw std::invalid_argument("trailing characters");
    return value;
  } catch (const std::exception&) {
    usage_error(flag + ": '" + text + "' is not a valid number");
  }
}

Args parse_args(int argc, char** argv) {
  Args a;
  std::vector<std::string> args(argv + 1, argv + argc);
  for (std::size_t i = 0; i < args.size(); ++i) {
    const std::string& arg = args[i];
    auto next = [&]() -> const std::string& {
      if (i + 1 >= args.size()) usage_error(arg + " needs a value");
      return args[++i];
    };
    if (arg == "-h" || arg == "--help") {
      std::cout << kUsage;
      std::exit(0);
    } else if (arg == "--out") {
      a.out = next();
    } else if (arg == "--method") {
      a.method = next();
    } else if (arg == "--sorm") {
      a.sorm = true;
    } else if (arg == "--importance-sampling") {
      a.importance_sampling = parse_number<long long>(arg, next());
    } else if (arg == "--monte-carlo") {
      a.monte_carlo = parse_number<long long>(arg, next());
    } else if (arg == "--seed") {
      a.seed = parse_number<unsigned long long>(arg, next());
    } else if (arg == "--max-iterations") {
      a.max_iterations = parse_number<int>(arg, next());
    } else if (arg == "--tolerance") {
      a.tolerance = parse_number<double>(arg, next());
    } else if (arg == "--server") {
      a.server = next();
    } else if (arg == "--token-file") {
      a.token_file = next();
    } else if (arg == "--gradients") {
      a.gradients = next();
    } else if (arg == "--fdm-eps") {
      a.fdm_eps = parse_number<double>(arg, next());
    } else if (arg == "--t-end") {
      a.t_end = parse_number<double>(arg, next());
    } else if (arg == "--threads") {
      a.threads = parse_number<int>(arg, next());
    } else if (arg.size() > 1 && arg[0] == '-') {
      usage_error("unknown option " + arg);
    } else if (a.problem.empty()) {
      a.problem = arg;
    } else {
      usage_error("more than one problem file given ('" + a.problem + "', '" + arg + "')");
    }
  }
  if (a.problem.empty()) usage_error("no problem file given");
  if (a.out.empty()) usage_error("--out DIR is required");
  if (!a.token_file.empty() && a.server.empty()) usage_error("--token-file needs --server");
  return a;
}

void print_errors(const std::vector<rel::FieldError>& errors) {
  for (const auto& e : errors) std::cerr << e.to_string() << "\n";
}

}  // namespace

int main(int argc, char** argv) {
  const Args args = parse_args(argc, argv);
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
    if (args.seed) options.seed = *args.seed;
    if (args.max_iterations) options.form.max_iterations = *args.max_iterations;
    if (args.tolerance) options.form.tolerance = *args.tolerance;
    for (const auto& e : options.validate()) errors.push_back(e);
    rel::EvaluatorOptions evaluator;
    evaluator.server = args.server;
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
      for (const char* flag : {"--server", "--gradients", "--fdm-eps", "--t-end"}) {
        const bool given = (std::string(flag) == "--server" && !args.server.empty()) ||
                           (std::string(flag) == "--gradients" && args.gradients) ||
                           (std::string(flag) == "--fdm-eps" && args.fdm_eps) ||
                           (std::string(flag) == "--t-end" && args.t_end);
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
