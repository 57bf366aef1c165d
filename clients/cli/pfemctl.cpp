// pfemctl: the command-line client of pfem-server.
//   pfemctl --server TARGET [--token-file F] [--tls-ca F] COMMAND ...
// TARGET: HOST:PORT, dns:///NAME:PORT or ipv4:A:P,B:P (round_robin over the addresses). Jobs
// live on the replica that took the SubmitJob: watch/result/cancel them through its own
// HOST:PORT; evaluate works through any target (retried on UNAVAILABLE).
//     validate MODEL
//     submit MODEL [--t-end T] [--dt DT] [--sensitivity none|ddm|fdm] [--params a,b]
//                  [--fdm-eps E] [--param name=value ...] [--timeout S]
//     watch ID
//     result ID --out DIR
//     cancel ID
//     list [--state queued|running|succeeded|failed|cancelled] [--limit N]
//     evaluate MODEL --functional RECORDER:KIND[:TIME] ... [--param name=value ...]
//                    [--params a,b] [--sensitivity ddm|fdm|none] [--fdm-eps E]
//                    [--t-end T] [--dt DT] [--no-cache] [--timeout S]
// submit prints the job id alone on the first line of stdout. watch exits 0 only when the job
// succeeded; it shows a progress bar on a terminal, otherwise a line a second at most (and
// one at every change of state, so the final state's line is always printed). Failed calls exit 1 with "STATUS_NAME: message" on stderr; usage errors exit 2.
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include "clients/cli/client.h"
#include "engine/analysis/functional.h"
#include "engine/cli/arguments.h"
#include "engine/io/model_io.h"
#include "engine/io/results_io.h"
#include "wire/convert.h"
#include "wire/status_name.h"

namespace {

constexpr const char* kUsage =
    "usage: pfemctl --server TARGET [--token-file F] [--tls-ca F] COMMAND ...\n"
    "TARGET: HOST:PORT, dns:///NAME:PORT or ipv4:A:P,B:P (round_robin over the replicas;\n"
    "jobs stay on the replica that took them, evaluate is retried on UNAVAILABLE)\n"
    "  validate MODEL\n"
    "  submit MODEL [--t-end T] [--dt DT] [--sensitivity none|ddm|fdm] [--params a,b]\n"
    "               [--fdm-eps E] [--param name=value ...] [--timeout S]\n"
    "  watch ID\n"
    "  result ID --out DIR\n"
    "  cancel ID\n"
    "  list [--state queued|running|succeeded|failed|cancelled] [--limit N]\n"
    "  evaluate MODEL --functional RECORDER:KIND[:TIME] ... [--param name=value ...]\n"
    "               [--params a,b] [--sensitivity ddm|fdm|none] [--fdm-eps E] [--t-end T]\n"
    "               [--dt DT] [--no-cache] [--timeout S]\n"
    "  KIND: at (value at TIME), max, min, max_abs, final\n";

// A failed call: exit 1 with the status name and message.
struct CallFailed {
  grpc::Status status;
};

// A usage error: exit 2.
struct UsageError : std::invalid_argument {
  using std::invalid_argument::invalid_argument;
};

void check(const grpc::Status& status) {
  if (!status.ok()) throw CallFailed{status};
}

std::string read_text(const std::string& file, const char* flag) {
  std::ifstream in(file, std::ios::binary);
  if (!in) throw UsageError(std::string(flag) + ": cannot read " + file);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

pfem::v1::Model load_model(const std::string& file) {
  try {
    return pfem::read_model_file(file);
  } catch (const pfem::ModelError& e) {
    throw CallFailed{{grpc::StatusCode::INVALID_ARGUMENT, e.what()}};
  }
}

pfem::v1::SensitivityMethod parse_method(const std::string& name) {
  if (name == "none") return pfem::v1::SENSITIVITY_METHOD_NONE;
  if (name == "ddm") return pfem::v1::SENSITIVITY_METHOD_DDM;
  if (name == "fdm") return pfem::v1::SENSITIVITY_METHOD_FDM;
  throw UsageError("--sensitivity: must be none, ddm or fdm");
}

// Every "--param name=value".
std::vector<pfem::v1::ParameterValue> take_params(pfem::cli::Arguments& a) {
  std::vector<pfem::v1::ParameterValue> out;
  while (auto s = a.take_string("--param")) {
    const auto eq = s->find('=');
    if (eq == std::string::npos || eq == 0) throw UsageError("--param: expected name=value, got " + *s);
    pfem::v1::ParameterValue v;
    v.set_name(s->substr(0, eq));
    try {
      std::size_t used = 0;
      v.set_value(std::stod(s->substr(eq + 1), &used));
      if (used != s->size() - eq - 1) throw std::invalid_argument("");
    } catch (const std::exception&) {
      throw UsageError("--param: '" + s->substr(eq + 1) + "' is not a number");
    }
    out.push_back(v);
  }
  return out;
}

std::string state_name(pfem::v1::JobState s) {
  std::string name = pfem::v1::JobState_Name(s);
  return name.rfind("JOB_STATE_", 0) == 0 ? name.substr(10) : name;
}

std::string format_seconds(double s) {
  char buf[32];
  if (s < 60) std::snprintf(buf, sizeof buf, "%.1fs", s);
  else std::snprintf(buf, sizeof buf, "%dm%02ds", static_cast<int>(s / 60), static_cast<int>(s) % 60);
  return buf;
}

class Ctl {
 public:
  explicit Ctl(pfem::client::ConnectionOptions options)
      : options_(std::move(options)),
        stub_(pfem::v1::GradientService::NewStub(pfem::client::make_channel(options_))) {}

  int validate(pfem::cli::Arguments& a) {
    a.expect_done(2);
    pfem::v1::ValidateModelRequest request;
    *request.mutable_model() = load_model(a.positional(1));
    pfem::v1::ValidateModelResponse response;
    auto context = make_context();
    check(stub_->ValidateModel(context.get(), request, &response));
    if (!response.valid()) {
      for (const auto& e : response.errors()) std::cerr << e.path() << ": " << e.message() << '\n';
      return 1;
    }
    std::cout << "valid: about " << response.estimated_particles() << " fluid particles, "
              << response.steps() << " steps\n";
    if (!response.over_limit().empty()) {
      std::cerr << "but this server would refuse to run it: " << response.over_limit() << '\n';
      return 1;
    }
    return 0;
  }

  int submit(pfem::cli::Arguments& a) {
    pfem::v1::SubmitJobRequest request;
    fill_options(a, request.mutable_options(), pfem::v1::SENSITIVITY_METHOD_NONE);
    for (auto& v : take_params(a)) *request.add_parameter_values() = v;
    if (auto t = a.take_double("--timeout")) request.set_timeout_seconds(*t);
    a.expect_done(2);
    *request.mutable_model() = load_model(a.positional(1));
    pfem::v1::SubmitJobResponse response;
    auto context = make_context();
    check(stub_->SubmitJob(context.get(), request, &response));
    std::cout << response.job_id() << std::endl;
    return 0;
  }

  int watch(pfem::cli::Arguments& a) {
    a.expect_done(2);
    pfem::v1::JobRequest request;
    request.set_job_id(a.positional(1));
    auto context = make_context();
    auto reader = stub_->WatchJob(context.get(), request);
    const bool tty = ::isatty(STDOUT_FILENO);
    pfem::v1::Job job;
    bool any = false;
    // Plain lines (not a terminal): one a second at most, and at every change of state.
    auto last_line = std::chrono::steady_clock::now() - std::chrono::hours(1);
    auto last_state = pfem::v1::JOB_STATE_UNSPECIFIED;
    while (reader->Read(&job)) {
      any = true;
      const auto now = std::chrono::steady_clock::now();
      if (tty || job.state() != last_state || now - last_line >= std::chrono::seconds(1)) {
        print_progress(job, tty);
        last_line = now;
        last_state = job.state();
      }
    }
    if (tty && any) std::cout << '\n';
    check(reader->Finish());
    std::cout << job.id() << ' ' << state_name(job.state());
    if (job.has_error() && !job.error().message().empty()) {
      std::cout << ": " << job.error().message() << " (step " << job.error().step()
                << ", t = " << job.error().time() << " s)";
    }
    std::cout << std::endl;
    return job.state() == pfem::v1::JOB_STATE_SUCCEEDED ? 0 : 1;
  }

  int result(pfem::cli::Arguments& a) {
    const auto out = a.take_string("--out");
    if (!out) throw UsageError("result: --out DIR is required");
    a.expect_done(2);
    pfem::v1::Result result;
    pfem::v1::Job job;
    check(pfem::client::fetch_result(*stub_, options_, a.positional(1), &result, &job));
    pfem::write_results(pfem::wire::from_proto(result), *out);
    std::cout << "wrote " << *out << ": " << result.responses().time_size() << " samples of "
              << result.responses().columns_size() << " responses";
    if (result.sensitivities().columns_size() > 0) {
      std::cout << " and " << result.sensitivities().columns_size() << " sensitivities";
    }
    std::cout << " (job " << state_name(job.state()) << ")\n";
    return 0;
  }

  int cancel(pfem::cli::Arguments& a) {
    a.expect_done(2);
    pfem::v1::JobRequest request;
    request.set_job_id(a.positional(1));
    pfem::v1::Job job;
    auto context = make_context();
    check(stub_->CancelJob(context.get(), request, &job));
    std::cout << job.id() << ' '
              << (job.state() == pfem::v1::JOB_STATE_RUNNING ? "cancelling"
                                                              : state_name(job.state()))
              << '\n';
    return 0;
  }

  int list(pfem::cli::Arguments& a) {
    pfem::v1::ListJobsRequest request;
    if (auto s = a.take_string("--state")) {
      std::string upper = "JOB_STATE_";
      for (char c : *s) upper += static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
      pfem::v1::JobState state;
      if (!pfem::v1::JobState_Parse(upper, &state)) throw UsageError("--state: unknown state " + *s);
      request.set_state(state);
    }
    if (auto n = a.take_int("--limit")) request.set_limit(*n);
    a.expect_done(1);
    pfem::v1::ListJobsResponse response;
    auto context = make_context();
    check(stub_->ListJobs(context.get(), request, &response));
    std::printf("%-16s  %-9s  %-20s  %11s  %s\n", "ID", "STATE", "MODEL", "STEP", "CREATED");
    for (const auto& job : response.jobs()) {
      char created[32] = "";
      const std::time_t t = static_cast<std::time_t>(job.created_unix());
      std::strftime(created, sizeof created, "%Y-%m-%d %H:%M:%S", std::localtime(&t));
      const std::string step = std::to_string(job.progress().step()) + "/" +
                               std::to_string(job.progress().total_steps());
      std::printf("%-16s  %-9s  %-20s  %11s  %s\n", job.id().c_str(),
                  state_name(job.state()).c_str(), job.model_name().substr(0, 20).c_str(),
                  step.c_str(), created);
    }
    return 0;
  }

  int evaluate(pfem::cli::Arguments& a) {
    pfem::v1::EvaluateRequest request;
    pfem::v1::RunOptions options;
    fill_options(a, &options, pfem::v1::SENSITIVITY_METHOD_DDM);
    if (options.has_t_end()) request.set_t_end(options.t_end());
    if (options.has_dt()) request.set_dt(options.dt());
    if (options.has_fdm_eps()) request.set_fdm_eps(options.fdm_eps());
    request.set_sensitivity(options.sensitivity());
    *request.mutable_params() = options.params();
    for (auto& v : take_params(a)) *request.add_parameter_values() = v;
    while (auto f = a.take_string("--functional")) *request.add_functionals() = parse_functional(*f);
    if (request.functionals().empty()) throw UsageError("evaluate: at least one --functional");
    request.set_no_cache(a.take_flag("--no-cache"));
    const auto timeout = a.take_double("--timeout");
    a.expect_done(2);
    *request.mutable_model() = load_model(a.positional(1));
    pfem::v1::EvaluateResponse response;
    // Evaluate gives the same answer on every replica: retried when one is UNAVAILABLE.
    check(pfem::client::call_with_retries(
        [&] {
          auto context = make_context();
          if (timeout) {
            context->set_deadline(std::chrono::system_clock::now() +
                                  std::chrono::milliseconds(static_cast<long>(*timeout * 1000)));
          }
          return stub_->Evaluate(context.get(), request, &response);
        },
        5));
    std::printf("%-24s %24s %12s", "functional", "value", "time");
    for (const auto& p : response.parameters()) std::printf(" %24s", ("d/d" + p).c_str());
    std::printf("\n");
    for (const auto& v : response.values()) {
      std::printf("%-24s %24.17g %12.6g", v.name().c_str(), v.value(), v.time());
      for (double g : v.gradient()) std::printf(" %24.17g", g);
      std::printf("\n");
    }
    std::printf("wall %.3f s%s, run %.3f s, %d steps\n", response.wall_seconds(),
                response.cached() ? " (cached)" : "", response.summary().wall_seconds(),
                response.summary().steps());
    return 0;
  }

 private:
  std::unique_ptr<grpc::ClientContext> make_context() {
    auto context = std::make_unique<grpc::ClientContext>();
    pfem::client::authorize(*context, options_);
    return context;
  }

  static void fill_options(pfem::cli::Arguments& a, pfem::v1::RunOptions* options,
                           pfem::v1::SensitivityMethod fallback) {
    if (auto v = a.take_double("--t-end")) options->set_t_end(*v);
    if (auto v = a.take_double("--dt")) options->set_dt(*v);
    if (auto v = a.take_double("--fdm-eps")) options->set_fdm_eps(*v);
    const auto method = a.take_string("--sensitivity");
    options->set_sensitivity(method ? parse_method(*method) : fallback);
    if (auto v = a.take_string("--params")) {
      for (const auto& p : pfem::cli::split(*v, ',')) options->add_params(p);
    }
  }

  static pfem::v1::Functional parse_functional(const std::string& text) {
    const auto parts = pfem::cli::split(text, ':');
    if (parts.size() < 2 || parts.size() > 3) {
      throw UsageError("--functional: expected RECORDER:KIND[:TIME], got " + text);
    }
    const auto kind = pfem::parse_functional_kind(parts[1]);
    if (!kind) throw UsageError("--functional: unknown kind '" + parts[1] + "'");
    pfem::v1::Functional f;
    f.set_recorder(parts[0]);
    f.set_name(text);
    switch (*kind) {
      case pfem::FunctionalKind::kValueAt: f.set_kind(pfem::v1::Functional::KIND_VALUE_AT); break;
      case pfem::FunctionalKind::kMax: f.set_kind(pfem::v1::Functional::KIND_MAX); break;
      case pfem::FunctionalKind::kMin: f.set_kind(pfem::v1::Functional::KIND_MIN); break;
      case pfem::FunctionalKind::kMaxAbs: f.set_kind(pfem::v1::Functional::KIND_MAX_ABS); break;
      case pfem::FunctionalKind::kFinal: f.set_kind(pfem::v1::Functional::KIND_FINAL); break;
    }
    if (*kind == pfem::FunctionalKind::kValueAt) {
      if (parts.size() != 3) throw UsageError("--functional: " + text + " needs a TIME");
      try {
        f.set_time(std::stod(parts[2]));
      } catch (const std::exception&) {
        throw UsageError("--functional: '" + parts[2] + "' is not a time");
      }
    } else if (parts.size() == 3) {
      throw UsageError("--functional: only 'at' takes a TIME");
    }
    return f;
  }

  static void print_progress(const pfem::v1::Job& job, bool tty) {
    const auto& p = job.progress();
    if (tty) {
      const int width = 30;
      const double fraction = p.total_steps() > 0 ? double(p.step()) / p.total_steps() : 0.0;
      const int filled = static_cast<int>(std::lround(fraction * width));
      std::printf("\r%-9s [%s%s] %3d%%  step %d/%d  t=%.4g s  newton %d  elapsed %s  left %s   ",
                  state_name(job.state()).c_str(), std::string(filled, '#').c_str(),
                  std::string(width - filled, '.').c_str(),
                  static_cast<int>(std::lround(100 * fraction)), p.step(), p.total_steps(),
                  p.time(), p.newton_iterations(), format_seconds(p.elapsed_seconds()).c_str(),
                  format_seconds(p.remaining_seconds()).c_str());
      std::fflush(stdout);
    } else {
      std::printf("%s step %d/%d t=%.6g newton=%d elapsed=%.3f remaining=%.3f\n",
                  state_name(job.state()).c_str(), p.step(), p.total_steps(), p.time(),
                  p.newton_iterations(), p.elapsed_seconds(), p.remaining_seconds());
      std::fflush(stdout);
    }
  }

  pfem::client::ConnectionOptions options_;
  std::unique_ptr<pfem::v1::GradientService::Stub> stub_;
};

}  // namespace

int main(int argc, char** argv) {
  pfem::cli::Arguments a(std::vector<std::string>(argv + 1, argv + argc));
  try {
    if (a.take_flag("--help") || a.take_flag("-h")) {
      std::cout << kUsage;
      return 0;
    }
    pfem::client::ConnectionOptions options;
    const auto server = a.take_string("--server");
    if (!server) throw UsageError("--server TARGET is required");
    options.server = *server;
    if (auto f = a.take_string("--token-file")) options.token = pfem::client::read_token_file(*f);
    if (auto f = a.take_string("--tls-ca")) options.tls_ca_pem = read_text(*f, "--tls-ca");
    // The command is the first positional argument.
    std::string command;
    try {
      command = a.positional(0);
    } catch (const std::out_of_range&) {
      throw UsageError("no command");
    }
    Ctl ctl(options);
    if (command == "validate") return ctl.validate(a);
    if (command == "submit") return ctl.submit(a);
    if (command == "watch") return ctl.watch(a);
    if (command == "result") return ctl.result(a);
    if (command == "cancel") return ctl.cancel(a);
    if (command == "list") return ctl.list(a);
    if (command == "evaluate") return ctl.evaluate(a);
    throw UsageError("unknown command '" + command + "'");
  } catch (const CallFailed& e) {
    std::cerr << "pfemctl: " << pfem::wire::status_code_name(e.status.error_code()) << ": "
              << e.status.error_message() << '\n';
    return 1;
  } catch (const std::invalid_argument& e) {
    std::cerr << "pfemctl: " << e.what() << '\n' << kUsage;
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "pfemctl: " << e.what() << '\n';
    return 1;
  }
}
