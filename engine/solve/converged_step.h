#pragma once
// What the DDM (step_sensitivity.h) reads of a converged PFEM step (fluid_step.h): the step at
// its converged iterate (step_iterate.h) and whether the Newton system was factorised there.
// References into the step, valid until it commits.
#include <span>

#include "engine/solve/bubble_history.h"
#include "engine/solve/condensed_bubble_system.h"
#include "engine/solve/step_iterate.h"

namespace pfem {

struct ConvergedStep : StepIterate {
  // The condensed system's factorisation is one of this step's iterates when newton_factorized
  // (the condensed formulation, and Newton factorised: water at rest can converge at its first
  // iterate).
  bool newton_factorized;
  std::span<const BubbleHistory::Sensitivity> bubbles_n;  // the bubbles' sensitivities at t_n
};

}  // namespace pfem
