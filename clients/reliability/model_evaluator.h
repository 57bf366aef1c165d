#pragma once
// Functionals of a PFEM model's recorders and their gradients with respect to named model
// parameters, for the reliability and optimisation drivers. Two ways to get them, behind one
// interface:
//   in-process   pfem::run (engine/analysis/run.h) + pfem::evaluate_functional
//                (engine/analysis/functional.h: the same code the server's Evaluate uses)
//   --server     the gRPC Evaluate of a pfem-server, or of several replicas behind one gRPC
//                target (round_robin); the model is stored with PutModel and evaluated by id
// Gradients by DDM (one run with the sensitivity solve) or by central finite differences (FDM:
// 2P + 1 value-only runs for P parameters, `concurrency` of them at a time); value-only calls
// run once without sensitivities.
#include <atomic>
#include <memory>
#include <optional>
#include <span>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "clients/reliability/errors.h"
#include "clients/reliability/simulation_stats.h"
#include "engine/analysis/functional.h"
#include "pfem/v1/model.pb.h"

namespace pfem::reliability {

enum class GradientMethod { kDdm, kFdm };
std::optional<GradientMethod> parse_gradient_method(std::string_view name);  // "ddm", "fdm"
std::string_view to_string(GradientMethod method);

// "at_time" (also "value_at", "at"), "max", "min", "max_abs", "final"; nullopt otherwise.
std::optional<FunctionalKind> parse_functional_name(std::string_view name);
// How reports show a functional: "max(tip_ux)", "at_time(tip_ux, t = 0.3)",
// "max_abs(tip_ux, 2 <= t <= 6)".
std::string functional_text(const FunctionalSpec& spec);
// The spec of a problem file's functional (pfem.v1 ModelLimitState or DesignQuantity: recorder,
// time and the optional window_start/window_end) of the given kind.
template <class Message>
FunctionalSpec functional_spec_of(const Message& m, FunctionalKind kind) {
  FunctionalSpec spec{m.recorder(), kind, m.time()};
  if (m.has_window_start()) spec.window_start = m.window_start();
  if (m.has_window_end()) spec.window_end = m.window_end();
  return spec;
}

struct EvaluatorOptions {
  std::string server;           // gRPC target of pfem-server(s); empty: run in-process
  std::string token;            // bearer token for the server (empty: none)
  GradientMethod gradients = GradientMethod::kDdm;
  double fdm_eps = 1e-7;        // relative step of the FDM
  std::optional<double> t_end;  // overrides the model's analysis.t_end
  int threads = 1;              // in-process: threads for the element loops
  double timeout_seconds = 3600.0;  // --server: deadline of one Evaluate call
  int concurrency = 1;          // FDM: how many of the 2P + 1 runs go at once
  int max_attempts = 5;         // --server: attempts of an Evaluate that fails UNAVAILABLE

  std::vector<FieldError> validate() const;  // paths "concurrency", "max_attempts", ...
};

// A failed evaluation: the simulation failed (the engine's message, with step and time), the
// parameter values are invalid for the model, or the server could not answer.
class ModelEvaluationError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct ModelEvaluation {
  std::vector<FunctionalValue> values;  // one per functional; gradient in `params` order
  int steps = 0;                        // steps of the run
  bool cached = false;                  // --server: from the server's cache
};

class ModelEvaluator {
 public:
  virtual ~ModelEvaluator() = default;
  // Sets the named model parameters to `values` (same order), runs, and evaluates the
  // functionals; with `gradient`, also d functional / d params[k]. Throws
  // ModelEvaluationError. Safe to call from several threads at once.
  ModelEvaluation evaluate(const std::vector<std::string>& params, std::span<const double> values,
                           const std::vector<FunctionalSpec>& functionals, bool gradient) const;
  // "in-process" or "server HOST:PORT".
  virtual std::string where() const = 0;
  GradientMethod gradient_method() const { return options_.gradients; }
  // e.g. "DDM (in-process)" or "FDM (central, 2P+1 runs; server 127.0.0.1:50051)".
  std::string gradient_source() const;
  SimulationStats stats() const;
  const EvaluatorOptions& options() const { return options_; }
  const pfem::v1::Model& model() const { return model_; }

 protected:
  ModelEvaluator(pfem::v1::Model model, EvaluatorOptions options)
      : model_(std::move(model)), options_(std::move(options)) {}
  // One run: values, and DDM gradients when `ddm_gradient`. Counts what it did.
  virtual ModelEvaluation run(const std::vector<std::string>& params, std::span<const double> values,
                              const std::vector<FunctionalSpec>& functionals,
                              bool ddm_gradient) const = 0;
  void count_run(bool cached) const;
  void count_retries(int retries) const { retries_ += retries; }

  pfem::v1::Model model_;
  EvaluatorOptions options_;

 private:
  ModelEvaluation finite_differences(const std::vector<std::string>& params,
                                     std::span<const double> values,
                                     const std::vector<FunctionalSpec>& functionals) const;

  mutable std::atomic<long long> evaluations_{0}, gradients_{0}, simulations_{0}, cached_{0};
  mutable std::atomic<long long> retries_{0};
  mutable std::atomic<long long> microseconds_{0};
};

// Checks the model (its own validation, and, with a server, the server's ValidateModel and
// PutModel) and returns the evaluator. Throws ModelEvaluationError naming every problem
// (field paths of the model, e.g. "structure.materials[0].fy: must be > 0") or the server's
// answer (e.g. "UNAVAILABLE: ..."); `path` prefixes the model's field paths.
std::unique_ptr<ModelEvaluator> make_evaluator(const pfem::v1::Model& model,
                                               const EvaluatorOptions& options,
                                               const std::string& path = "model");

// Names of the model's parameters and recorders (for validation by the drivers).
std::vector<std::string> model_parameter_names(const pfem::v1::Model& model);
std::vector<std::string> model_recorder_names(const pfem::v1::Model& model);
// The value a parameter has in the model (pfem::parameter_values): its `value`, or else the value
// of its first target once the other parameters' values are set. nullopt when there is no
// parameter of that name or a target names no value.
std::optional<double> model_parameter_value(const pfem::v1::Model& model, const std::string& name);

}  // namespace pfem::reliability
