#pragma once
// Reliability-problem files: proto3 JSON of pfem.v1.ReliabilityProblem -> message -> the
// library's domain objects (marginals, Nataf transform, limit state), with validation that
// names the field path of every error ("variables[1].stddev: must be > 0").
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "clients/reliability/errors.h"
#include "clients/reliability/form.h"
#include "clients/reliability/limit_state.h"
#include "clients/reliability/nataf.h"
#include "pfem/v1/reliability.pb.h"

namespace pfem::reliability {

// Parses proto3 JSON (unknown fields are errors). Throws ProblemError with the field path.
pfem::v1::ReliabilityProblem parse_problem_json(std::string_view json);
// Reads and parses a file. Throws ProblemError (also when the file cannot be read).
pfem::v1::ReliabilityProblem read_problem_file(const std::filesystem::path& path);

enum class LimitStateKind { kExpression, kModel };

// A validated problem, ready for analysis.
struct Problem {
  std::string name;
  std::string description;
  std::vector<std::string> names;            // variable names, in file order
  std::vector<Distribution> marginals;       // same order
  std::optional<NatafTransform> transform;   // always set by build_problem
  LimitStateKind limit_state_kind = LimitStateKind::kExpression;
  std::string expression;                    // kExpression
  FormMethod method = FormMethod::kIhlrf;
  pfem::v1::ReliabilityProblem message;      // the source (the model limit state reads it)
};

// Every problem of the message, in field order (including expression parse errors with their
// column and unattainable correlations); empty when it is valid.
std::vector<FieldError> validate_problem(const pfem::v1::ReliabilityProblem& message);

// Validates and builds. Throws ProblemError with every error.
Problem build_problem(const pfem::v1::ReliabilityProblem& message);

// The limit state of a built expression problem. Throws NotAvailableError for a model limit
// state: that one needs the engine or a server, see make_limit_state(problem, EvaluatorOptions)
// in clients/reliability/model_limit_state.h (library pfem_reliability_model).
std::unique_ptr<LimitState> make_limit_state(const Problem& problem);

}  // namespace pfem::reliability
