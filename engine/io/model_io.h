#pragma once
// Model files: proto3 JSON of pfem.v1.Model -> message, and validation with field paths.
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "engine/base/field_error.h"
#include "pfem/v1/model.pb.h"

namespace pfem {

// Parses proto3 JSON (unknown fields are errors). Throws ModelError.
pfem::v1::Model parse_model_json(std::string_view json);
pfem::v1::Model read_model_file(const std::filesystem::path& path);

// Every problem of the model, in field order; empty when it is valid.
std::vector<FieldError> validate_model(const pfem::v1::Model& model);

}  // namespace pfem
