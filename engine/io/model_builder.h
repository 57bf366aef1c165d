#pragma once
// pfem.v1.Model -> Problem: defaults applied, parameter values set on their targets, walls
// and fluid regions discretised into nodes, recorder targets resolved to nodes.
#include <string>
#include <vector>

#include "engine/io/problem.h"
#include "engine/io/model_io.h"
#include "pfem/v1/model.pb.h"

namespace pfem {

// Validates first; throws ModelError listing every problem. sensitivity_params: the names of
// the model's parameters to differentiate by DDM (seeds on the fluid and the structure, and
// sensitivity storage on the nodes); the caller checks that they exist.
Problem build_problem(const pfem::v1::Model& model, const std::vector<std::string>& sensitivity_params = {});

// build_problem of a model that validate_model has passed already (it is not validated again);
// throws ModelError for what only building finds.
Problem build_validated_problem(const pfem::v1::Model& model,
                                const std::vector<std::string>& sensitivity_params = {});

// Every problem with the model: validate_model's, or when it passes, what building it finds
// (a fluid region with no particle clear of the walls, a domain that leaves out a node).
std::vector<FieldError> model_errors(const pfem::v1::Model& model);

}  // namespace pfem
