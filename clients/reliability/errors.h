#pragma once
// Input errors of the reliability library: each names the field path and the rule it broke,
// e.g. {"variables[1].stddev", "must be > 0"}.
#include <stdexcept>
#include <string>
#include <vector>

namespace pfem::reliability {

struct FieldError {
  std::string path;
  std::string message;
  std::string to_string() const { return path.empty() ? message : path + ": " + message; }
  bool operator==(const FieldError&) const = default;
};

// Thrown for an invalid problem or invalid options; what() holds every error, one per line.
class ProblemError : public std::runtime_error {
 public:
  explicit ProblemError(std::vector<FieldError> errors)
      : std::runtime_error(join(errors)), errors_(std::move(errors)) {}
  const std::vector<FieldError>& errors() const { return errors_; }

 private:
  static std::string join(const std::vector<FieldError>& errors) {
    std::string out;
    for (const auto& e : errors) {
      if (!out.empty()) out += '\n';
      out += e.to_string();
    }
    return out;
  }
  std::vector<FieldError> errors_;
};

// Thrown when a problem is valid but asks for something this build cannot do yet (a model
// limit state).
class NotAvailableError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace pfem::reliability
