// libFuzzer target: a model file's way through `pfem validate` and the server, i.e. the proto3
// JSON parser, validation, and building (engine/io), for models within the server's default
// cost limits (a larger model's cost is bounded by those limits, not a defect).
// Expected outcomes: a model, or ModelError naming the field. Anything else is a defect.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "engine/io/model_builder.h"
#include "engine/io/model_io.h"
#include "server/limits.h"
#include "server/model_cost.h"
#include "server/status.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  pfem::v1::Model model;
  try {
    model = pfem::parse_model_json(std::string_view(reinterpret_cast<const char*>(data), size));
  } catch (const pfem::ModelError&) {
    return 0;
  }
  const pfem::server::Limits limits;
  try {
    pfem::server::check_run_limits(model, std::nullopt, std::nullopt, limits);
  } catch (const pfem::server::ServiceError&) {
    return 0;
  }
  if (!pfem::validate_model(model).empty() || !pfem::server::polygon_errors(model).empty()) {
    return 0;
  }
  try {
    const auto problem = pfem::build_problem(model);
  } catch (const pfem::ModelError&) {
  }
  return 0;
}
