#pragma once
// pfem.v1.Model -> Problem: defaults applied, parameter values set on their targets, walls
// and fluid regions discretised into nodes, recorder targets resolved to nodes.
#include <string>
#include <vector>

#include "engine/analysis/problem.h"
#include "pfem/v1/model.pb.h"

namespace pfem {

// Validates first; throws ModelError listing every problem. sensitivity_params: the names of
// the model's parameters to differentiate by DDM (seeds on the fluid and the structure, and
// sensitivity storage on the nodes); the caller checks that they exist.
Problem build_problem(const pfem::v1::Model& model, const std::vector<std::string>& sensitivity_params = {});

}  // namespace pfem
