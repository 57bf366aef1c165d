// The `pfem` command: run and validate model files (design.md, "Contracts").
//   pfem run MODEL.json --out DIR [--t-end T] [--dt DT] [--sensitivity none|ddm|fdm]
//            [--params a,b] [--fdm-eps E] [--vtk-every N] [--vtk] [--threads N] [--progress]
//            [--checkpoint-every N] [--formulation quasi-incompressible|incompressible]
//   pfem run --restart DIR [MODEL.json] [--out DIR] [--threads N] [--progress] [--checkpoint-every N]
//   pfem check-gradients MODEL.json [--params a,b] [--t-end T] [--dt DT] [--fdm-eps E]
//            [--tolerance TOL] [--threads N] [--formulation F]
// --formulation sets the model's analysis.formulation for this run.
//   pfem validate MODEL.json     (every error; then warnings and the run's estimated size and time)
// `pfem run` prints a progress line on stderr when stderr is a terminal (or with --progress);
// SIGINT or SIGTERM stops it at the end of the step in progress and writes every output with
// status "cancelled" (a second signal ends it at once). With --checkpoint-every N it writes
// DIR/checkpoint.pfem after every N-th step and when cancelled; --restart DIR continues from it
// with the checkpointed run's model and options, bit-identically to a run never stopped.
// Exit codes: 0 success, 1 simulation failed or cancelled (check-gradients: or a DDM column off
// the FDM by more than the tolerance), 2 invalid input or usage.
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <optional>
#include <algorithm>
#include <iostream>
#include <string>
#include <vector>

#include "engine/analysis/checkpoint.h"
#include "engine/analysis/gradient_check.h"
#include "engine/analysis/run.h"
#include "engine/analysis/run_estimate.h"
#include "engine/cli/arguments.h"
#include "engine/io/model_builder.h"
#include "engine/io/model_io.h"
#include "engine/io/model_warnings.h"
#include "engine/io/results_io.h"

namespace {

const char* kUsage =
    "usage: pfem run MODEL.json --out DIR [--t-end T] [--dt DT] [--sensitivity none|ddm|fdm]\n"
    "                [--params a,b] [--fdm-eps E] [--vtk] [--vtk-every N] [--threads N] [--progress]\n"
    "                [--checkpoint-every N] [--formulation quasi-incompressible|incompressible]\n"
    "       pfem run --restart DIR [MODEL.json] [--out DIR] [--threads N] [--progress] [--checkpoint-every N]\n"
    "       pfem check-gradients MODEL.json [--params a,b] [--t-end T] [--dt DT] [--fdm-eps E]\n"
    "                [--tolerance TOL] [--threads N] [--formulation F]\n"
    "       pfem validate MODEL.json\n";

// Set by SIGINT/SIGTERM (a lock-free atomic store is async-signal-safe).
std::atomic<bool> g_stop_requested{false};
// Where the handler also stops the engine at once, or null: the FDM's perturbed runs have no
// progress callback that could pass the request on at the end of a step.
std::atomic<bool>* g_stop_now = nullptr;

extern "C" void on_stop_signal(int signal) {
  g_stop_requested.store(true);
  if (g_stop_now) g_stop_now->store(true);
  std::signal(signal, SIG_DFL);  // a second Ctrl-C ends the process at once
}

// The progress line: rewritten in place on a terminal (at most 10 times a second), one line a
// second otherwise; always the last step.
class ProgressLine {
 public:
  explicit ProgressLine(bool terminal) : terminal_(terminal) {}
  void show(const pfem::Progress& p) {
    const auto now = std::chrono::steady_clock::now();
    if (p.step < p.total_steps && now - last_ < std::chrono::milliseconds(terminal_ ? 100 : 1000)) return;
    last_ = now;
    std::fprintf(stderr, "%sstep %d/%d  t = %.4f s  newton %d  %.1f s elapsed, %.1f s left%s", terminal_ ? "\r" : "",
                 p.step, p.total_steps, p.time, p.newton_iterations, p.elapsed_seconds, p.remaining_seconds,
                 terminal_ ? "   " : "\n");
    shown_ = true;
  }
  void end() const {
    if (terminal_ && shown_) std::fprintf(stderr, "\n");
  }

 private:
  bool terminal_;
  bool shown_ = false;
  std::chrono::steady_clock::time_point last_{};
};

// "42 s", "3.5 min", "2.1 h", "4.0 days".
std::string duration(double seconds) {
  char buf[32];
  if (seconds < 120) std::snprintf(buf, sizeof buf, "%.2g s", seconds);
  else if (seconds < 7200) std::snprintf(buf, sizeof buf, "%.1f min", seconds / 60);
  else if (seconds < 172800) std::snprintf(buf, sizeof buf, "%.1f h", seconds / 3600);
  else std::snprintf(buf, sizeof buf, "%.1f days", seconds / 86400);
  return buf;
}

int usage_error(const std::string& message) {
  std::cerr << "pfem: " << message << "\n" << kUsage;
  return 2;
}

// "" when dir is (or can be made) a directory a file can be written in; otherwise why not.
std::string writable_directory(const std::string& dir) {
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec) return "cannot create " + dir + ": " + ec.message();
  if (!std::filesystem::is_directory(dir)) return dir + " is not a directory";
  const std::filesystem::path probe = std::filesystem::path(dir) / ".pfem-write-test";
  if (!std::ofstream(probe)) return "cannot write in " + dir;
  std::filesystem::remove(probe, ec);
  return "";
}

// --formulation F: "" when F is one (it then takes the place of the model's
// analysis.formulation), else the usage error.
std::string check_formulation(const std::optional<std::string>& f) {
  if (!f || *f == "quasi-incompressible" || *f == "incompressible") return "";
  return "--formulation must be quasi-incompressible or incompressible";
}

// The model file with --formulation's choice, if given.
pfem::v1::Model with_formulation(pfem::v1::Model model, const std::optional<std::string>& f) {
  if (f) model.mutable_analysis()->set_formulation(*f);
  return model;
}

// Runs body; invalid input (ModelError) prints one line per field and gives exit code 2, any
// other error one line and exit code 1.
int with_exit_codes(const std::function<int()>& body) {
  try {
    return body();
  } catch (const pfem::CheckpointError& e) {
    std::cerr << "pfem: " << e.what() << "\n";
    return 2;
  } catch (const pfem::ModelError& e) {
    for (const auto& err : e.errors()) std::cerr << err.to_string() << "\n";
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "pfem: " << e.what() << "\n";
    return 1;
  }
}

// Errors (exit 2), else "valid"; then the warnings and the run's estimated size and time.
int validate(const std::vector<std::string>& args) {
  if (args.size() != 1) return usage_error("validate takes one model file");
  try {
    const auto model = pfem::read_model_file(args[0]);
    const auto errors = pfem::model_errors(model);
    for (const auto& e : errors) std::cerr << e.to_string() << "\n";
    if (errors.empty()) std::cout << args[0] << ": valid\n";
    if (errors.empty())
      for (const auto& w : pfem::model_warnings(model)) std::cerr << "warning: " << w.to_string() << "\n";
    if (const auto e = pfem::estimate_run(model); e.particles > 0 && e.steps > 0)
      std::printf("estimate: %ld particles, about %ld elements, %ld steps, about %s (response only, 1 thread, "
                  "at %.2g us per particle and step measured here)\n",
                  e.particles, e.elements, e.steps, duration(e.seconds).c_str(), e.seconds_per_particle_step * 1e6);
    return errors.empty() ? 0 : 2;
  } catch (const pfem::ModelError& e) {
    for (const auto& err : e.errors()) std::cerr << err.to_string() << "\n";
    return 2;
  }
}

constexpr const char* kCheckpointFile = "checkpoint.pfem";

// The checkpoint of --restart DIR (DIR/checkpoint.pfem, or DIR itself when it is a file).
std::filesystem::path checkpoint_in(const std::string& dir) {
  return std::filesystem::is_directory(dir) ? std::filesystem::path(dir) / kCheckpointFile : std::filesystem::path(dir);
}

// A restart's run options: the checkpointed run's; flags that would change them are refused.
int restart_options(pfem::cli::Arguments& a, const pfem::Checkpoint& c, pfem::RunOptions& options, bool& vtk) {
  for (const char* flag : {"--t-end", "--dt", "--sensitivity", "--params", "--fdm-eps", "--vtk-every", "--formulation"})
    if (a.take_string(flag)) return usage_error(std::string(flag) + ": a restart continues with the checkpointed run's options");
  if (a.take_flag("--vtk")) return usage_error("--vtk: a restart continues with the checkpointed run's options");
  options.t_end = c.run.t_end, options.dt = c.run.dt;
  options.sensitivity = c.run.sensitivity;
  options.params = c.run.params;
  options.drop_geometric_terms = c.run.drop_geometric_terms;
  options.vtk_every = c.run.vtk_every;
  vtk = c.run.vtk;
  return 0;
}

int run(const std::vector<std::string>& args) {
  pfem::cli::Arguments a(args);
  pfem::RunOptions options;
  std::string out_dir;
  bool vtk = false, show_progress = false;
  std::optional<pfem::Checkpoint> restart;
  std::optional<std::string> formulation;
  try {
    out_dir = a.take_string("--out").value_or("");
    if (auto r = a.take_string("--restart")) {
      options.restart_from = checkpoint_in(*r);
      restart = pfem::read_checkpoint(options.restart_from);
      if (out_dir.empty()) out_dir = options.restart_from.parent_path().string();
      if (out_dir.empty()) out_dir = ".";
      if (const int code = restart_options(a, *restart, options, vtk); code != 0) return code;
    } else {
      options.t_end = a.take_double("--t-end");
      options.dt = a.take_double("--dt");
      if (auto m = a.take_string("--sensitivity")) {
        if (*m == "none") options.sensitivity = pfem::SensitivityMethod::kNone;
        else if (*m == "ddm") options.sensitivity = pfem::SensitivityMethod::kDdm;
        else if (*m == "fdm") options.sensitivity = pfem::SensitivityMethod::kFdm;
        else return usage_error("--sensitivity must be none, ddm or fdm");
      }
      if (auto p = a.take_string("--params")) options.params = pfem::cli::split(*p, ',');
      if (auto e = a.take_double("--fdm-eps")) options.fdm_eps = *e;
      if (auto v = a.take_int("--vtk-every")) options.vtk_every = *v, vtk = true;
      vtk = a.take_flag("--vtk") || vtk;
      formulation = a.take_string("--formulation");
      if (const std::string why = check_formulation(formulation); !why.empty()) return usage_error(why);
    }
    if (auto n = a.take_int("--checkpoint-every")) {
      if (*n < 1) return usage_error("--checkpoint-every must be >= 1");
      options.checkpoint_every = *n;
    }
    if (auto t = a.take_int("--threads")) options.threads = *t;
    show_progress = a.take_flag("--progress");
    a.expect_done(restart ? std::min<std::size_t>(a.remaining(), 1) : 1);  // a restart's model is optional
  } catch (const std::invalid_argument& e) {
    return usage_error(e.what());
  } catch (const pfem::CheckpointError& e) {
    std::cerr << "pfem: --restart: " << e.what() << "\n";
    return 2;
  }
  if (out_dir.empty()) return usage_error("run needs --out DIR");
  if (!options.params.empty() && options.sensitivity == pfem::SensitivityMethod::kNone)
    return usage_error("--params needs --sensitivity ddm or fdm");
  if (const std::string why = writable_directory(out_dir); !why.empty()) {
    std::cerr << "pfem: --out: " << why << "\n";
    return 2;
  }
  if (vtk) options.vtk_dir = out_dir + "/vtk";
  if (options.checkpoint_every > 0) options.checkpoint_file = std::filesystem::path(out_dir) / kCheckpointFile;

  const bool terminal = isatty(fileno(stderr));
  show_progress = show_progress || terminal;
  ProgressLine line(terminal);
  std::atomic<bool> cancel{false};
  options.cancel = &cancel;
  // The request takes effect when the step in progress ends: the callback runs after every step.
  options.progress = [&](const pfem::Progress& p) {
    if (g_stop_requested.load()) cancel.store(true);
    if (show_progress) line.show(p);
  };
  if (options.sensitivity == pfem::SensitivityMethod::kFdm) g_stop_now = &cancel;
  std::signal(SIGINT, on_stop_signal);
  std::signal(SIGTERM, on_stop_signal);
  return with_exit_codes([&] {
    const auto model =
        a.remaining() == 0 ? restart->run.model : with_formulation(pfem::read_model_file(a.positional(0)), formulation);
    const pfem::RunResult result = pfem::run(model, options);
    line.end();
    pfem::write_results(result, out_dir);
    const auto& s = result.summary;
    for (const auto& w : s.warnings) std::cerr << "pfem: warning: " << w << "\n";
    if (s.status != pfem::RunStatus::kCompleted) {
      std::cerr << "pfem: " << s.message << " (partial results in " << out_dir << ")\n";
      if (s.status == pfem::RunStatus::kCancelled && options.checkpoint_every > 0 &&
          std::filesystem::exists(options.checkpoint_file))
        std::cerr << "pfem: continue with: pfem run --restart " << out_dir << "\n";
      return 1;
    }
    std::printf("%d steps, %d particles, up to %d elements, %ld Newton iterations, %.2f s (response %.2f s, sensitivity %.2f s)\n",
                s.steps, s.particles, s.max_elements, s.newton_iterations, s.wall_seconds,
                s.response_seconds, s.sensitivity_seconds);
    std::printf("results in %s\n", out_dir.c_str());
    return 0;
  });
}

// Runs DDM, DDM without H and T, and central FDM; prints one row per recorder and parameter.
int check_gradients(const std::vector<std::string>& args) {
  pfem::cli::Arguments a(args);
  pfem::RunOptions options;
  double tolerance = 1e-3;
  std::optional<std::string> formulation;
  try {
    options.t_end = a.take_double("--t-end");
    options.dt = a.take_double("--dt");
    if (auto p = a.take_string("--params")) options.params = pfem::cli::split(*p, ',');
    if (auto e = a.take_double("--fdm-eps")) options.fdm_eps = *e;
    if (auto t = a.take_double("--tolerance")) tolerance = *t;
    if (!(tolerance > 0.0)) return usage_error("--tolerance must be > 0");
    if (auto t = a.take_int("--threads")) options.threads = *t;
    formulation = a.take_string("--formulation");
    if (const std::string why = check_formulation(formulation); !why.empty()) return usage_error(why);
    a.expect_done(1);
  } catch (const std::invalid_argument& e) {
    return usage_error(e.what());
  }
  return with_exit_codes([&] {
    const auto model = with_formulation(pfem::read_model_file(a.positional(0)), formulation);
    const pfem::GradientCheck check = pfem::check_gradients(model, options, true);
    for (const auto& w : check.fdm.warnings) std::cerr << "pfem: warning: " << w << "\n";
    for (const auto* s : {&check.ddm, &check.fdm}) {
      if (s->status != pfem::RunStatus::kCompleted) {
        std::cerr << "pfem: " << (s == &check.ddm ? "DDM" : "FDM") << " run stopped: " << s->message << "\n";
        return 1;
      }
    }
    const bool approximate = check.ddm.sensitivity_method == "ddm-approximate";
    std::printf(
        "%s to t = %g s (%d steps): %s %.1f s (response %.1f s + sensitivity %.1f s), central FDM "
        "(eps %g) %.1f s\n",
        a.positional(0).c_str(), check.ddm.t_end, check.ddm.steps,
        approximate ? "DDM (ddm-approximate: the incompressible formulation's)" : "DDM", check.ddm.wall_seconds,
        check.ddm.response_seconds, check.ddm.sensitivity_seconds, options.fdm_eps, check.fdm.wall_seconds);
    std::printf("max over time of |DDM - FDM| / max |FDM|\n");
    std::printf("%-16s %-12s %12s %12s %14s\n", "recorder", "parameter", "max |FDM|", "DDM", "without H,T");
    bool pass = true;
    int compared = 0, negligible = 0, not_a_slope = 0, unmoved = 0;
    for (const auto& r : check.rows) {
      char mark[64] = "";
      if (r.negligible) {
        std::snprintf(mark, sizeof mark, "  negligible"), ++negligible;
      } else if (r.not_a_slope) {
        std::snprintf(mark, sizeof mark, "  FDM not a slope"), ++not_a_slope;
      } else if (r.unmoved) {
        // Its ratio is 0 or inf: its DDM's own size says whether that is round-off.
        std::snprintf(mark, sizeof mark, "  unmoved, max |DDM| %.2e", r.max_ddm), ++unmoved;
      } else {
        ++compared;
        pass = pass && r.ddm <= tolerance;
      }
      std::printf("%-16s %-12s %12.4e %12.2e %14.2e%s\n", r.recorder.c_str(), r.parameter.c_str(), r.max_fdm, r.ddm,
                  r.without_geometric, mark);
    }
    // A check that compared nothing has verified nothing.
    pass = pass && compared > 0;
    std::printf("DDM within %g of FDM: %s, %d of %zu columns", tolerance, pass ? "yes" : "NO", compared,
                check.rows.size());
    std::vector<std::string> left_out;
    if (negligible > 0) {
      char text[100];
      std::snprintf(text, sizeof text, "%d negligible: |d| < %g max |r| / |theta| in both", negligible,
                    pfem::kNegligibleSensitivity);
      left_out.push_back(text);
    }
    if (not_a_slope > 0)
      left_out.push_back(std::to_string(not_a_slope) + " whose FDM is not a slope: see the warnings");
    if (unmoved > 0) left_out.push_back(std::to_string(unmoved) + " unmoved: the response and its FDM 0 throughout");
    for (std::size_t i = 0; i < left_out.size(); ++i)
      std::printf("%s%s", i == 0 ? " (not compared: " : "; ", left_out[i].c_str());
    if (!left_out.empty()) std::printf(")");
    std::printf("\n");
    return pass ? 0 : 1;
  });
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) return usage_error("missing command");
  const std::string command = argv[1];
  const std::vector<std::string> args(argv + 2, argv + argc);
  if (command == "run") return run(args);
  if (command == "validate") return validate(args);
  if (command == "check-gradients") return check_gradients(args);
  if (command == "--help" || command == "-h") {
    std::cout << kUsage;
    return 0;
  }
  return usage_error("unknown command '" + command + "'");
}
