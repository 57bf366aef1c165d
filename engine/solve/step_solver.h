#pragma once
// What the time loop (engine/analysis/simulation.cpp) asks of the solver of one PFEM step: the
// response on a fixed mesh, its sensitivities, the commit of both to the nodes (three calls, as
// the loop reads in docs/design.md: response -> DDM -> commit), a report of its work, and saving
// or restoring what it hands to the next step. A model's analysis.formulation picks the
// implementation:
//  - "quasi-incompressible" (default): UnifiedStep (fluid_step.h), Newton on the unified
//    velocity-pressure system of pdot/kappa + div v = 0, with the exact DDM (theory §4, §5);
//  - "incompressible": FractionalStep (fractional_step.h), div v = 0 by Zhu & Scott's improved
//    fractional step, with the approximate DDM the paper compares against (theory §8).
// StepSettings, StepReport and the exceptions a step throws (StepFailure, StepCancelled) are
// declared with UnifiedStep in fluid_step.h.
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
  // The step's response from the nodes at t_n (x, v, p and their sensitivities), iterated to
  // convergence; the nodes are not changed. Throws StepFailure (the caller retries the step
  // shorter) or StepCancelled.
  virtual void solve(const mesh::FluidMesh& mesh, const StepSettings& settings, const NodeState& nodes,
                     const std::atomic<bool>* cancel) = 0;
  // The DDM of the step solve() converged (nothing without parameters); may throw StepFailure.
  virtual void solve_sensitivities(const mesh::FluidMesh& mesh, const StepSettings& settings,
                                   const NodeState& nodes) = 0;
  // The converged step and its sensitivities to the nodes, now at t_{n+1}.
  virtual void commit(const mesh::FluidMesh& mesh, const StepSettings& settings, NodeState& nodes) = 0;
  // The three in a row (nodes unchanged when one throws); the step's report.
  const StepReport& advance(const mesh::FluidMesh& mesh, const StepSettings& settings, NodeState& nodes,
                            const std::atomic<bool>* cancel = nullptr) {
    solve(mesh, settings, nodes, cancel);
    solve_sensitivities(mesh, settings, nodes);
    commit(mesh, settings, nodes);
    return last_report();
  }
  // The report of the last call, also when it threw (the work of a failed attempt).
  virtual const StepReport& last_report() const = 0;
  // Saves or restores what one step hands to the next, for a checkpoint; between steps only.
  virtual void archive(StateArchive& a) = 0;
};

}  // namespace pfem
