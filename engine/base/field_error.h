#pragma once
// Input errors with the field path they concern, shared by every layer that checks input
// (model validation, run options, the reliability drivers' options).
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace pfem {

// One problem with the input, e.g. {"structure.materials[1].fy", "must be > 0"}.
struct FieldError {
  std::string path;
  std::string message;
  std::string to_string() const { return path.empty() ? message : path + ": " + message; }
  bool operator==(const FieldError&) const = default;
};

namespace detail {
// Every error, one "path: message" a line.
inline std::string join_field_errors(const std::vector<FieldError>& errors) {
  std::string out;
  for (const auto& e : errors) {
    if (!out.empty()) out += '\n';
    out += e.to_string();
  }
  return out;
}
}  // namespace detail

// Thrown for invalid input; what() joins every error, one per line.
class ModelError : public std::runtime_error {
 public:
  explicit ModelError(std::vector<FieldError> errors)
      : std::runtime_error(detail::join_field_errors(errors)), errors_(std::move(errors)) {}
  ModelError(std::string path, std::string message)
      : ModelError(std::vector<FieldError>{{std::move(path), std::move(message)}}) {}
  const std::vector<FieldError>& errors() const { return errors_; }

 private:
  std::vector<FieldError> errors_;
};

}  // namespace pfem
