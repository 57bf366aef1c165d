#pragma once
// Input errors of the reliability library: each names the field path and the rule it broke,
// e.g. {"variables[1].stddev", "must be > 0"}.
#include <stdexcept>
#include <string>
#include <vector>

#include "engine/base/field_error.h"

namespace pfem::reliability {

using pfem::FieldError;

// Thrown for an invalid problem or invalid options; what() holds every error, one per line.
class ProblemError : public std::runtime_error {
 public:
  explicit ProblemError(std::vector<FieldError> errors)
      : std::runtime_error(pfem::detail::join_field_errors(errors)), errors_(std::move(errors)) {}
  const std::vector<FieldError>& errors() const { return errors_; }

 private:
  std::vector<FieldError> errors_;
};

// Thrown when a problem is valid but asks for something this build cannot do yet (a model
// limit state).
class NotAvailableError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace pfem::reliability
