#pragma once
// pfem.v1.Model -> Problem: defaults applied, parameter values set on their targets, walls
// and fluid regions discretised into nodes, recorder targets resolved to nodes.
#include "engine/analysis/problem.h"
#include "pfem/v1/model.pb.h"

namespace pfem {

// Validates first; throws ModelError listing every problem.
Problem build_problem(const pfem::v1::Model& model);

}  // namespace pfem
