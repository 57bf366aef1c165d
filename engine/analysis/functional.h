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
// arg-max time is the derivative that holds almost everywhere.)
#include <optional>
#include <span>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "engine/analysis/run.h"

namespace pfem {

enum class FunctionalKind { kValueAt, kMax, kMin, kMaxAbs, kFinal };

struct FunctionalSpec {
  std::string recorder;  // a response column (recorder name)
  FunctionalKind kind = FunctionalKind::kFinal;
  double time = 0.0;     // for kValueAt [s]
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

// "at" / "value_at", "max", "min", "max_abs" / "absmax", "final"; nullopt otherwise.
std::optional<FunctionalKind> parse_functional_kind(std::string_view name);
// "value_at", "max", "min", "max_abs", "final".
std::string functional_kind_name(FunctionalKind kind);

}  // namespace pfem
