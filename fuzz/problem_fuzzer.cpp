// libFuzzer target: the reliability and optimisation problem files (clients/reliability),
// each input read as both: the proto3 JSON parser, validation, building, and for an
// expression limit state its parsed expression. Expected outcomes: a problem, or
// ProblemError naming the field. Anything else is a defect.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "clients/reliability/optimize.h"
#include "clients/reliability/problem_io.h"

namespace {

void reliability(std::string_view json) {
  namespace rel = pfem::reliability;
  try {
    const rel::Problem problem = rel::build_problem(rel::parse_problem_json(json));
    if (problem.limit_state_kind == rel::LimitStateKind::kExpression) {
      rel::make_limit_state(problem);
    }
  } catch (const rel::ProblemError&) {
  }
}

void optimisation(std::string_view json) {
  namespace opt = pfem::optimize;
  try {
    opt::build_problem(opt::parse_problem_json(json));
  } catch (const pfem::reliability::ProblemError&) {
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view json(reinterpret_cast<const char*>(data), size);
  reliability(json);
  optimisation(json);
  return 0;
}
