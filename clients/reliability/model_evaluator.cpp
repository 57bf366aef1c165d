#include "clients/reliability/model_evaluator.h"

#include <chrono>
#include <cmath>
#include <mutex>
#include <sstream>

#include "clients/cli/client.h"
#include "clients/reliability/json_writer.h"
#include "clients/reliability/parallel.h"
#include "clients/reliability/report.h"
#include "engine/analysis/run.h"
#include "engine/io/model_io.h"
#include "engine/io/parameter_targets.h"
#include "pfem/v1/service.grpc.pb.h"

namespace pfem::reliability {

namespace {

using Clock = std::chrono::steady_clock;

std::string join_errors(const std::vector<pfem::FieldError>& errors, const std::string& prefix) {
  std::string out;
  for (const auto& e : errors) {
    if (!out.empty()) out += '\n';
    out += (e.path.empty() ? prefix : prefix + "." + e.path) + ": " + e.message;
  }
  return out;
}

// The model with the named parameters set to values.
pfem::v1::Model with_values(const pfem::v1::Model& model, const std::vector<std::string>& params,
                            std::span<const double> values) {
  pfem::v1::Model m = model;
  for (std::size_t k = 0; k < params.size(); ++k) {
    for (auto& p : *m.mutable_parameters()) {
      if (p.name() == params[k]) p.set_value(values[k]);
    }
  }
  return m;
}

std::string describe_values(const std::vector<std::string>& params, std::span<const double> values) {
  std::ostringstream s;
  s.precision(10);
  for (std::size_t k = 0; k < params.size(); ++k) s << (k ? ", " : "") << params[k] << " = " << values[k];
  return s.str();
}

class LocalEvaluator final : public ModelEvaluator {
 public:
  LocalEvaluator(pfem::v1::Model model, EvaluatorOptions options)
      : ModelEvaluator(std::move(model), std::move(options)) {}

  std::string where() const override { return "in-process"; }

  ModelEvaluation run(const std::vector<std::string>& params, std::span<const double> values,
                      const std::vector<FunctionalSpec>& functionals,
                      bool gradient) const override {
    pfem::RunOptions o;
    o.t_end = options_.t_end;
    o.threads = options_.threads;
    if (gradient) {
      o.sensitivity = pfem::SensitivityMethod::kDdm;
      o.params = params;
    }
    pfem::RunResult r;
    try {
      r = pfem::run(with_values(model_, params, values), o);
    } catch (const pfem::ModelError& e) {
      throw ModelEvaluationError("the model is invalid at " + describe_values(params, values) +
                                 ": " + join_errors(e.errors(), "model"));
    }
    count_run(false);
    if (r.summary.status != pfem::RunStatus::kCompleted) {
      throw ModelEvaluationError("the simulation failed at step " +
                                 std::to_string(r.summary.failed_step) + " (t = " +
                                 std::to_string(r.summary.failed_time) + " s) with " +
                                 describe_values(params, values) + ": " + r.summary.message);
    }
    ModelEvaluation out;
    out.steps = r.summary.steps;
    const std::vector<std::string> none;
    for (const auto& spec : functionals) {
      try {
        out.values.push_back(
            evaluate_functional(r.responses, r.sensitivities, gradient ? params : none, spec));
      } catch (const FunctionalError& e) {
        throw ModelEvaluationError("functional of '" + spec.recorder + "': " + e.what());
      }
    }
    return out;
  }
};

pfem::v1::Functional::Kind to_wire(FunctionalKind kind) {
  switch (kind) {
    case FunctionalKind::kValueAt: return pfem::v1::Functional::KIND_VALUE_AT;
    case FunctionalKind::kMax: return pfem::v1::Functional::KIND_MAX;
    case FunctionalKind::kMin: return pfem::v1::Functional::KIND_MIN;
    case FunctionalKind::kMaxAbs: return pfem::v1::Functional::KIND_MAX_ABS;
    case FunctionalKind::kFinal: return pfem::v1::Functional::KIND_FINAL;
  }
  return pfem::v1::Functional::KIND_UNSPECIFIED;
}

std::string status_text(const grpc::Status& s) {
  static const char* names[] = {"OK", "CANCELLED", "UNKNOWN", "INVALID_ARGUMENT",
                                "DEADLINE_EXCEEDED", "NOT_FOUND", "ALREADY_EXISTS",
                                "PERMISSION_DENIED", "RESOURCE_EXHAUSTED", "FAILED_PRECONDITION",
                                "ABORTED", "OUT_OF_RANGE", "UNIMPLEMENTED", "INTERNAL",
                                "UNAVAILABLE", "DATA_LOSS", "UNAUTHENTICATED"};
  const int code = static_cast<int>(s.error_code());
  const std::string name = code >= 0 && code <= 16 ? names[code] : std::to_string(code);
  return name + ": " + s.error_message();
}

class RemoteEvaluator final : public ModelEvaluator {
 public:
  RemoteEvaluator(pfem::v1::Model model, EvaluatorOptions options, const std::string& path)
      : ModelEvaluator(std::move(model), std::move(options)) {
    connection_.server = options_.server;
    connection_.token = options_.token;
    stub_ = pfem::v1::GradientService::NewStub(pfem::client::make_channel(connection_));
    {  // The server's own validation (it may have limits the local one does not know).
      pfem::v1::ValidateModelRequest request;
      *request.mutable_model() = model_;
      pfem::v1::ValidateModelResponse response;
      const auto status = pfem::client::call_with_retries(
          [&] {
            grpc::ClientContext context;
            prepare(context, 60.0);
            return stub_->ValidateModel(&context, request, &response);
          },
          options_.max_attempts);
      if (!status.ok()) {
        throw ModelEvaluationError("server " + options_.server + ": " + status_text(status));
      }
      if (!response.valid()) {
        std::string text;
        for (const auto& e : response.errors()) {
          if (!text.empty()) text += '\n';
          text += (e.path().empty() ? path : path + "." + e.path()) + ": " + e.message();
        }
        throw ModelEvaluationError(text);
      }
    }
    pfem::v1::PutModelRequest request;
    *request.mutable_model() = model_;
    pfem::v1::PutModelResponse response;
    const auto status = pfem::client::call_with_retries(
        [&] {
          grpc::ClientContext context;
          prepare(context, 60.0);
          return stub_->PutModel(&context, request, &response);
        },
        options_.max_attempts);
    if (!status.ok()) {
      throw ModelEvaluationError("server " + options_.server + ": PutModel: " + status_text(status));
    }
    model_id_ = response.model_id();
  }

  std::string where() const override { return "server " + options_.server; }

  ModelEvaluation run(const std::vector<std::string>& params, std::span<const double> values,
                      const std::vector<FunctionalSpec>& functionals,
                      bool gradient) const override {
    pfem::v1::EvaluateRequest request;
    request.set_model_id(model_id_);
    for (std::size_t k = 0; k < params.size(); ++k) {
      auto* v = request.add_parameter_values();
      v->set_name(params[k]);
      v->set_value(values[k]);
    }
    for (const auto& spec : functionals) {
      auto* f = request.add_functionals();
      f->set_recorder(spec.recorder);
      f->set_kind(to_wire(spec.kind));
      f->set_time(spec.time);
      if (spec.window_start) f->set_window_start(*spec.window_start);
      if (spec.window_end) f->set_window_end(*spec.window_end);
    }
    if (gradient) {
      request.set_sensitivity(pfem::v1::SENSITIVITY_METHOD_DDM);
      for (const auto& p : params) request.add_params(p);
    } else {
      request.set_sensitivity(pfem::v1::SENSITIVITY_METHOD_NONE);
    }
    if (options_.t_end) request.set_t_end(*options_.t_end);
    pfem::v1::EvaluateResponse response;
    const auto call = [&] {
      grpc::ClientContext context;
      prepare(context, options_.timeout_seconds);
      response.Clear();
      return stub_->Evaluate(&context, request, &response);
    };
    int retries = 0;
    grpc::Status status = pfem::client::call_with_retries(call, options_.max_attempts, &retries);
    if (status.error_code() == grpc::StatusCode::NOT_FOUND) {
      // The replica that answered never saw the PutModel (e.g. one added by scaling): the
      // same request with the model itself.
      *request.mutable_model() = model_;
      status = pfem::client::call_with_retries(call, options_.max_attempts, &retries);
    }
    count_retries(retries);
    if (!status.ok()) {
      // A simulation failure is FAILED_PRECONDITION with the engine's message.
      const std::string at = " (" + describe_values(params, values) + ")";
      if (status.error_code() == grpc::StatusCode::FAILED_PRECONDITION) {
        count_run(false);
        throw ModelEvaluationError(status.error_message() + at);
      }
      throw ModelEvaluationError("server " + options_.server + ": " + status_text(status) + at);
    }
    count_run(response.cached());
    if (response.values_size() != static_cast<int>(functionals.size()) ||
        (gradient && response.parameters_size() != static_cast<int>(params.size()))) {
      throw ModelEvaluationError("server " + options_.server + ": malformed Evaluate response");
    }
    ModelEvaluation out;
    out.steps = response.summary().steps();
    out.cached = response.cached();
    for (const auto& v : response.values()) {
      FunctionalValue f;
      f.value = v.value();
      f.time = v.time();
      if (gradient) {
        // The server answers in its parameters order; map to ours.
        f.gradient.assign(params.size(), 0.0);
        for (int j = 0; j < response.parameters_size(); ++j) {
          for (std::size_t k = 0; k < params.size(); ++k) {
            if (response.parameters(j) == params[k] && j < v.gradient_size()) {
              f.gradient[k] = v.gradient(j);
            }
          }
        }
      }
      out.values.push_back(std::move(f));
    }
    return out;
  }

 private:
  void prepare(grpc::ClientContext& context, double seconds) const {
    pfem::client::authorize(context, connection_);
    context.set_deadline(std::chrono::system_clock::now() +
                         std::chrono::microseconds(static_cast<long long>(seconds * 1e6)));
  }

  pfem::client::ConnectionOptions connection_;
  std::unique_ptr<pfem::v1::GradientService::Stub> stub_;
  std::string model_id_;
};

}  // namespace

std::optional<GradientMethod> parse_gradient_method(std::string_view name) {
  if (name == "ddm") return GradientMethod::kDdm;
  if (name == "fdm") return GradientMethod::kFdm;
  return std::nullopt;
}

std::string_view to_string(GradientMethod method) {
  return method == GradientMethod::kDdm ? "ddm" : "fdm";
}

std::optional<FunctionalKind> parse_functional_name(std::string_view name) {
  if (name == "at_time") return FunctionalKind::kValueAt;
  return parse_functional_kind(name);
}

std::string functional_text(const FunctionalSpec& spec) {
  const auto number = [](double v) { return JsonWriter::number(v); };
  std::string text = (spec.kind == FunctionalKind::kValueAt ? std::string("at_time")
                                                            : functional_kind_name(spec.kind)) +
                     "(" + spec.recorder;
  if (spec.kind == FunctionalKind::kValueAt) text += ", t = " + number(spec.time);
  return text + time_window_text(spec.window_start, spec.window_end) + ")";
}

std::string ModelEvaluator::gradient_source() const {
  const std::string method = options_.gradients == GradientMethod::kDdm
                                 ? "DDM"
                                 : "FDM (central, 2P+1 runs, eps " +
                                       [&] {
                                         std::ostringstream s;
                                         s << options_.fdm_eps;
                                         return s.str();
                                       }() + ")";
  return method + ", " + where();
}

std::vector<FieldError> EvaluatorOptions::validate() const {
  std::vector<FieldError> errors;
  if (!(fdm_eps > 0 && fdm_eps < 0.1)) errors.push_back({"fdm_eps", "must be in (0, 0.1)"});
  if (t_end && !(std::isfinite(*t_end) && *t_end > 0)) errors.push_back({"t_end", "must be > 0"});
  if (threads < 1) errors.push_back({"threads", "must be >= 1"});
  if (concurrency < 1) errors.push_back({"concurrency", "must be >= 1"});
  if (max_attempts < 1) errors.push_back({"max_attempts", "must be >= 1"});
  return errors;
}

ModelEvaluation ModelEvaluator::evaluate(const std::vector<std::string>& params,
                                         std::span<const double> values,
                                         const std::vector<FunctionalSpec>& functionals,
                                         bool gradient) const {
  const auto start = Clock::now();
  struct Timer {  // counts the call's time also when it throws
    const Clock::time_point start;
    std::atomic<long long>& total;
    ~Timer() {
      total += std::chrono::duration_cast<std::chrono::microseconds>(Clock::now() - start).count();
    }
  } timer{start, microseconds_};
  ++evaluations_;
  if (gradient) ++gradients_;
  if (gradient && options_.gradients == GradientMethod::kFdm) {
    return finite_differences(params, values, functionals);
  }
  return run(params, values, functionals, gradient);
}

// Central differences of the functionals, step eps |value| (eps where the value is 0), the
// engine's rule; run 0 is the point itself (its values are the answer's values), runs 2k + 1
// and 2k + 2 parameter k plus and minus its step. Every run is independent: `concurrency` at once.
ModelEvaluation ModelEvaluator::finite_differences(const std::vector<std::string>& params,
                                                   std::span<const double> values,
                                                   const std::vector<FunctionalSpec>& functionals) const {
  const std::size_t p = params.size();
  std::vector<double> steps(p);
  for (std::size_t k = 0; k < p; ++k) {
    steps[k] = options_.fdm_eps * (values[k] != 0.0 ? std::abs(values[k]) : 1.0);
  }
  std::vector<ModelEvaluation> runs(2 * p + 1);
  parallel_for(runs.size(), options_.concurrency, [&](std::size_t i) {
    std::vector<double> x(values.begin(), values.end());
    if (i > 0) x[(i - 1) / 2] += (i % 2 == 1 ? 1.0 : -1.0) * steps[(i - 1) / 2];
    runs[i] = run(params, x, functionals, false);
  });
  ModelEvaluation out = std::move(runs[0]);
  for (std::size_t f = 0; f < out.values.size(); ++f) {
    out.values[f].gradient.resize(p);
    for (std::size_t k = 0; k < p; ++k) {
      out.values[f].gradient[k] =
          (runs[2 * k + 1].values[f].value - runs[2 * k + 2].values[f].value) / (2.0 * steps[k]);
    }
  }
  return out;
}

void ModelEvaluator::count_run(bool cached) const {
  if (cached) {
    ++cached_;
  } else {
    ++simulations_;
  }
}

SimulationStats ModelEvaluator::stats() const {
  SimulationStats s;
  s.evaluations = evaluations_;
  s.gradient_evaluations = gradients_;
  s.simulations = simulations_;
  s.cached = cached_;
  s.retries = retries_;
  s.seconds = static_cast<double>(microseconds_.load()) * 1e-6;
  return s;
}

std::unique_ptr<ModelEvaluator> make_evaluator(const pfem::v1::Model& model,
                                               const EvaluatorOptions& options,
                                               const std::string& path) {
  if (const auto errors = pfem::validate_model(model); !errors.empty()) {
    throw ModelEvaluationError(join_errors(errors, path));
  }
  if (const auto errors = options.validate(); !errors.empty()) {
    std::string text;
    for (const auto& e : errors) text += (text.empty() ? "" : "\n") + e.to_string();
    throw ModelEvaluationError(text);
  }
  if (options.server.empty()) return std::make_unique<LocalEvaluator>(model, options);
  return std::make_unique<RemoteEvaluator>(model, options, path);
}

std::vector<std::string> model_parameter_names(const pfem::v1::Model& model) {
  std::vector<std::string> names;
  for (const auto& p : model.parameters()) names.push_back(p.name());
  return names;
}

std::vector<std::string> model_recorder_names(const pfem::v1::Model& model) {
  std::vector<std::string> names;
  for (const auto& r : model.recorders()) names.push_back(r.name());
  return names;
}

std::optional<double> model_parameter_value(const pfem::v1::Model& model, const std::string& name) {
  pfem::v1::Model with_values = model;
  try {
    pfem::apply_parameter_overrides(with_values);
    const std::vector<double> values = pfem::parameter_values(with_values);
    for (int i = 0; i < model.parameters_size(); ++i) {
      if (model.parameters(i).name() == name) return values[i];
    }
  } catch (const pfem::ModelError&) {
  }
  return std::nullopt;
}

}  // namespace pfem::reliability
