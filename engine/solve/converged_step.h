#pragma once
// What the DDM (step_sensitivity.h) reads of a converged PFEM step (fluid_step.h): the
// numbering, the iterate, the elements' terms there and the Newton system's analysis and
// factorisation. References into the step, valid until it commits.
#include <Eigen/Core>

#include "engine/mesh/remesher.h"
#include "engine/solve/condensed_bubble_system.h"
#include "engine/solve/step_elements.h"
#include "engine/solve/step_numbering.h"
#include "engine/solve/step_structure.h"

namespace pfem {

struct StepSettings;

struct ConvergedStep {
  const mesh::FluidMesh& mesh;
  const StepSettings& settings;
  const StepNumbering& num;
  const Eigen::VectorXd& v;        // the converged iterate
  const Eigen::VectorXd& p;
  const StepElements& elements;    // at the converged iterate
  const StepResidual& residual;    // assembled there (its pressure mass)
  const StepStructure& structure;  // its trial state there
  // The condensed Newton system, analysed in this step; its factorisation is one of this step's
  // iterates when newton_factorized (the condensed formulation, and Newton factorised: water at
  // rest can converge at its first iterate).
  const CondensedBubbleSystem& condensed;
  bool newton_factorized;
  const Eigen::MatrixXd& bubbles_n;  // the bubbles' sensitivities at t_n (2 rows a triangle)
};

}  // namespace pfem
