#pragma once
// Everything one step of simulate() hands to the next: what a checkpoint saves after a step and
// a restart restores (engine/analysis/checkpoint.h). The Problem is not part of it: a restart
// rebuilds it from the same model.
#include <memory>
#include <optional>

#include "engine/analysis/simulation.h"
#include "engine/analysis/water_account.h"
#include "engine/mesh/remesher.h"
#include "engine/solve/node_state.h"
#include "engine/solve/step_solver.h"
#include "engine/state/state_archive.h"
#include "engine/structure/structure_model.h"

namespace pfem {

struct RunState {
  NodeState nodes;
  // The mesh of the last step: the next remeshing reads its free surface and contact edges.
  mesh::FluidMesh mesh;
  std::optional<structure::StructureModel> structure;  // with its history and sensitivities
  // The model's formulation's step (make_step_solver): UnifiedStep (bubbles by triangle, LU
  // analysis) or FractionalStep.
  std::unique_ptr<StepSolver> solver;
  WaterAccount water;                                  // the volume correction's target
  // The histories so far and the summary's counts (summary.steps: the steps done).
  SimulationOutput out;
};

// The step of the problem's formulation (Problem::incompressible).
std::unique_ptr<StepSolver> make_step_solver(const Problem& problem);

// Saves or restores the state; the structure's presence must match (a restored state lands in
// a RunState made from the same problem).
void archive(StateArchive& a, RunState& state);

}  // namespace pfem
