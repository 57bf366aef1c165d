#include "engine/io/model_io.h"

#include <google/protobuf/util/json_util.h>

#include <fstream>
#include <sstream>

#include "engine/base/json_errors.h"
#include "engine/io/model_checks.h"

namespace pfem {

pfem::v1::Model parse_model_json(std::string_view json) {
  pfem::v1::Model model;
  google::protobuf::util::JsonParseOptions options;
  options.ignore_unknown_fields = false;
  const auto status = google::protobuf::util::JsonStringToMessage(
      google::protobuf::StringPiece(json.data(), json.size()), &model, options);
  if (!status.ok())
    throw ModelError(json_errors(json, *pfem::v1::Model::descriptor(), "model", std::string(status.message())));
  return model;
}

pfem::v1::Model read_model_file(const std::filesystem::path& path) {
  if (std::filesystem::is_directory(path)) throw ModelError(path.string(), "is a directory, not a model file");
  std::ifstream in(path);
  if (!in) throw ModelError(path.string(), "cannot open the model file");
  std::stringstream buffer;
  buffer << in.rdbuf();
  return parse_model_json(buffer.str());
}

std::vector<FieldError> validate_model(const pfem::v1::Model& model) {
  ModelChecker checker(model);
  return checker.run();
}

}  // namespace pfem
