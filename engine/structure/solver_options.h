#pragma once
// Options and summary shared by the structure-alone solvers.
#include <string>

namespace pfem::structure {

struct NewtonOptions {
  int max_iterations = 30;
  // Converged when ||r|| <= relative_tolerance * ref + absolute_tolerance on the free dofs,
  // ref = max(||F_ext scaled||, ||r|| at the first iteration of the step).
  double relative_tolerance = 1e-10;
  double absolute_tolerance = 0.0;
};

struct SolveSummary {
  bool converged = true;
  int steps = 0;               // steps completed
  int newton_iterations = 0;   // total over the steps
  double residual_norm = 0.0;  // of the last iteration
  std::string message;         // why it failed (empty when converged)
};

}  // namespace pfem::structure
