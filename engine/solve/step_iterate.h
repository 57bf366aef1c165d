#pragma once
// A PFEM step (fluid_step.h) at one Newton iterate, as the step's linear systems
// (step_linear_system.h) and its exact Jacobian (step_jacobian.h) read it: the numbering, the
// iterate, the elements' terms there and the condensed Newton system's analysis. References into
// the step, valid while the iterate stays.
#include <Eigen/Core>

#include "engine/mesh/remesher.h"
#include "engine/solve/step_elements.h"
#include "engine/solve/step_numbering.h"
#include "engine/solve/step_structure.h"

namespace pfem {

struct StepSettings;
class CondensedBubbleSystem;

struct StepIterate {
  const mesh::FluidMesh& mesh;
  const StepSettings& settings;
  const StepNumbering& num;
  const Eigen::VectorXd& v;  // the iterate
  const Eigen::VectorXd& p;
  const StepElements& elements;    // at the iterate
  const StepResidual& residual;    // assembled there (its pressure mass)
  const StepStructure& structure;  // its trial state there
  // The condensed Newton system: its analysis (in this step, once it has factorised or
  // analysed) is the exact Jacobian's.
  const CondensedBubbleSystem& condensed;
};

}  // namespace pfem
