#pragma once
// The Newton loop's tests on the history of its relative residuals (engine/solve/fluid_step.h):
// converged, stalled (refactorise at the current iterate) and hopeless (give the step up: the
// caller retries it shorter).
#include <vector>

namespace pfem {

class NewtonMonitor {
 public:
  // Iterations in which the smallest residual so far must at least halve.
  static constexpr int kStallWindow = 10;

  NewtonMonitor(double tolerance, int max_iterations) : tolerance_(tolerance), max_iterations_(max_iterations) {}

  // The residual of the next iteration (0, 1, ...).
  void record(double residual);
  int iteration() const { return static_cast<int>(residuals_.size()) - 1; }
  double residual() const { return residuals_.back(); }

  bool converged() const { return residual() <= tolerance_; }
  bool out_of_iterations() const { return iteration() >= max_iterations_; }
  // The smallest residual has not even halved in the last kStallWindow iterations (diverging or
  // cycling: a splash the step is too long for), from iteration 2 kStallWindow on: a halved
  // step is cheaper than the rest of max_iterations, each with a factorisation.
  bool hopeless() const;
  // This residual is above half the previous one.
  bool stalled() const;

 private:
  double tolerance_;
  int max_iterations_;
  std::vector<double> residuals_, best_;  // best_: the smallest residual up to each iteration
};

}  // namespace pfem
