#pragma once
// What the time loop (engine/analysis/simulation.cpp) asks of the solver of one PFEM step: advance
// the nodes by a step on a fixed mesh, report its work, and save or restore what it hands to the
// next step. A model's analysis.formulation picks the implementation:
//  - "quasi-incompressible" (default): UnifiedStep (fluid_step.h), Newton on the unified
//    velocity-pressure system of pdot/kappa + div v = 0, with the exact DDM (theory §4, §5);
//  - "incompressible": FractionalStep (fractional_step.h), div v = 0 by Zhu & Scott's improved
//    fractional step, with the approximate DDM the paper compares against (theory §8).
// StepSettings, StepReport and the exceptions a step throws (StepFailure, StepCancelled) are
// declared with UnifiedStep in fluid_step.h; include it to call advance().
#include <atomic>

#include "engine/mesh/remesher.h"
#include "engine/solve/node_state.h"
#include "engine/state/state_archive.h"

namespace pfem {

struct StepSettings;
struct StepReport;

class StepSolver {
 public:
  virtual ~StepSolver() = default;
  // nodes hold x, v, p (and their sensitivities) at t_n on entry and at t_{n+1} on return.
  // Throws StepFailure (the caller retries the step shorter) or StepCancelled; nodes are then
  // left unchanged.
  virtual StepReport advance(const mesh::FluidMesh& mesh, const StepSettings& settings, NodeState& nodes,
                             const std::atomic<bool>* cancel = nullptr) = 0;
  // The report of the last call, also when it threw (the work of a failed attempt).
  virtual const StepReport& last_report() const = 0;
  // Saves or restores what one step hands to the next, for a checkpoint; between steps only.
  virtual void archive(StateArchive& a) = 0;
};

}  // namespace pfem
