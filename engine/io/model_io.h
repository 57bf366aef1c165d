#pragma once
// Model files: proto3 JSON of pfem.v1.Model -> message, and validation with field paths.
#include <filesystem>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "pfem/v1/model.pb.h"

namespace pfem {

// One problem with the input, e.g. {"structure.materials[1].fy", "must be > 0"}.
struct FieldError {
  std::string path;
  std::string message;
  std::string to_string() const { return path + ": " + message; }
};

// Thrown for invalid input; what() joins every error, one per line.
class ModelError : public std::runtime_error {
 public:
  explicit ModelError(std::vector<FieldError> errors);
  ModelError(std::string path, std::string message)
      : ModelError(std::vector<FieldError>{{std::move(path), std::move(message)}}) {}
  const std::vector<FieldError>& errors() const { return errors_; }

 private:
  std::vector<FieldError> errors_;
};

// Parses proto3 JSON (unknown fields are errors). Throws ModelError.
pfem::v1::Model parse_model_json(std::string_view json);
pfem::v1::Model read_model_file(const std::filesystem::path& path);

// Every problem of the model, in field order; empty when it is valid.
std::vector<FieldError> validate_model(const pfem::v1::Model& model);

}  // namespace pfem
