#pragma once
// Static Newton under load control: the model's nodal loads F are applied in load_steps equal
// increments, lambda_k = lambda_0 + (1 - lambda_0) k / load_steps, solving
// Fs_int(u) = lambda_k F from the last committed state (lambda_0 = initial_load_factor: the
// factor already in equilibrium there, 0 for an unloaded start); each converged step is
// committed. On failure (no convergence, singular tangent, collapsed element) the model is
// reverted to the last converged step and the summary says where it stopped.
#include "engine/structure/solver_options.h"
#include "engine/structure/structure_model.h"

namespace pfem::structure {

struct StaticOptions {
  int load_steps = 1;                // >= 1
  double initial_load_factor = 0.0;  // lambda_0
  NewtonOptions newton;
};

SolveSummary solve_static(StructureModel& model, const StaticOptions& options = {});

}  // namespace pfem::structure
