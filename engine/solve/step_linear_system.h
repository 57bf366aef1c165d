#pragma once
// The Newton matrix of a step and its solve (engine/solve/fluid_step.h), by one of two block
// eliminations with the same solution: the paper's global-bubble formulation
// (global_bubble_system.h) or the bubble condensed per element (condensed_bubble_system.h).
// One factorisation serves several Newton iterations; between them only the structure's block
// may follow the iterate.
#include <Eigen/Core>

#include "engine/mesh/remesher.h"
#include "engine/solve/step_elements.h"
#include "engine/solve/step_numbering.h"
#include "engine/solve/step_structure.h"

namespace pfem {

struct StepSettings;

class StepLinearSystem {
 public:
  virtual ~StepLinearSystem() = default;
  // A new step: its mesh, settings, numbering and structure, which must outlive it.
  virtual void begin(const mesh::FluidMesh& mesh, const StepSettings& s, const StepNumbering& num,
                     const StepStructure& structure) = 0;
  // Assembles and factorises the Newton matrix at the iterate of elements' last update, mp the
  // pressure mass assembled there; analyze at the step's first factorisation (a new pattern).
  // Throws std::runtime_error when it cannot be factorised.
  virtual void factorize(const StepElements& elements, const Eigen::VectorXd& mp, bool analyze) = 0;
  // Brings the factorisation's structure block to the structure's tangent at the current
  // iterate where the formulation does so cheaply; false when the matrix must be refactorised.
  virtual bool refresh_structure() = 0;
  // The Newton correction (dv, dp) of the residual r by the last factorisation.
  virtual void solve(const StepResidual& r, Eigen::VectorXd& dv, Eigen::VectorXd& dp) const = 0;
};

}  // namespace pfem
