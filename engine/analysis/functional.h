#pragma once
// Scalar functionals of a recorder's history and their gradients, from the response and
// sensitivity histories of one run (pfem::RunResult). Used by the server's Evaluate RPC, pfemctl
// and the reliability and optimisation drivers (no gRPC, no I/O).
//
//   kValueAt  r(t)       linear between the two samples around t; gradient interpolated alike
//   kFinal    r(t_last)  gradient: the sensitivities at the last sample
//   kMax      max r      gradient: the sensitivities at the arg-max sample (first on ties)
//   kMin      min r      gradient: the sensitivities at the arg-min sample
//   kMaxAbs   max |r|    gradient: sign(r) times the sensitivities at the arg-max sample
// (max/min are not differentiable where the extreme switches samples; the value at the
// arg-max time is the derivative that holds almost everywhere.) max, min and max_abs may be
// limited to the samples in a time window [window_start, window_end], e.g. to leave out a
// start-up transient and take the largest response to the steady waves that follow.
#include <optional>
#include <span>
#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "engine/analysis/run.h"

namespace pfem {

enum class FunctionalKind { kValueAt, kMax, kMin, kMaxAbs, kFinal };

struct FunctionalSpec {
  FunctionalSpec() = default;
  FunctionalSpec(std::string recorder_name, FunctionalKind functional_kind, double at_time = 0.0)
      : recorder(std::move(recorder_name)), kind(functional_kind), time(at_time) {}
  std::string recorder;  // a response column (recorder name)
  FunctionalKind kind = FunctionalKind::kFinal;
  double time = 0.0;     // for kValueAt [s]
  std::optional<double> window_start;  // kMax/kMin/kMaxAbs: only samples at t >= this [s]
  std::optional<double> window_end;    // kMax/kMin/kMaxAbs: only samples at t <= this [s]
};

struct FunctionalValue {
  double value = 0.0;
  double time = 0.0;             // the time the value is taken at [s]
  std::vector<double> gradient;  // d value / d params[k]; empty when params is empty
};

// A bad spec or missing history. field() names the FunctionalSpec member at fault
// ("recorder", "time") or "sensitivities" when a sensitivity column is missing.
class FunctionalError : public std::invalid_argument {
 public:
  FunctionalError(std::string field, const std::string& message)
      : std::invalid_argument(message), field_(std::move(field)) {}
  const std::string& field() const { return field_; }

 private:
  std::string field_;
};

// Evaluates spec on the histories. The gradient has one entry per name in params, read from
// the sensitivity columns "d<recorder>/d<param>". Throws FunctionalError.
FunctionalValue evaluate_functional(const Histories& responses, const Histories& sensitivities,
                                    std::span<const std::string> params,
                                    const FunctionalSpec& spec);

// Checks the window of a spec (finite, start <= end, only with max, min and max_abs); empty
// when it is fine, otherwise {"window_start" or "window_end", reason}.
std::optional<std::pair<std::string, std::string>> check_functional_window(
    const FunctionalSpec& spec);

// "at" / "value_at", "max", "min", "max_abs" / "absmax", "final"; nullopt otherwise.
std::optional<FunctionalKind> parse_functional_kind(std::string_view name);
// "value_at", "max", "min", "max_abs", "final".
std::string functional_kind_name(FunctionalKind kind);

}  // namespace pfem
