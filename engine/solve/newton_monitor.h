#pragma once
// The Newton loop's tests on the history of its relative residuals and of whether a triangle
// was inverted at each iterate (engine/solve/fluid_step.h): converged, stalled (refactorise at
// the current iterate) and hopeless (give the step up: the caller retries it shorter).
#include <vector>

namespace pfem {

class NewtonMonitor {
 public:
  // Iterations in which the smallest residual so far must at least halve.
  static constexpr int kStallWindow = 10;

  // Inverted and stagnating (below): from this iteration on, when the smallest residual has not
  // fallen kInvertedDrop-fold in the last kInvertedWindow iterations.
  static constexpr int kInvertedFrom = 6;
  static constexpr int kInvertedWindow = 3;
  static constexpr double kInvertedDrop = 10.0;

  // give_up_inverted: whether an inverted, stagnating iterate makes the step hopeless (not on a
  // step that can no longer be retried shorter).
  NewtonMonitor(double tolerance, int max_iterations, bool give_up_inverted = false)
      : tolerance_(tolerance), max_iterations_(max_iterations), give_up_inverted_(give_up_inverted) {}

  // The residual of the next iteration (0, 1, ...) and whether a triangle is inverted there.
  void record(double residual, bool inverted = false);
  int iteration() const { return static_cast<int>(residuals_.size()) - 1; }
  double residual() const { return residuals_.back(); }

  bool converged() const { return residual() <= tolerance_; }
  bool out_of_iterations() const { return iteration() >= max_iterations_; }
  // The smallest residual has not even halved in the last kStallWindow iterations (diverging or
  // cycling: a splash the step is too long for), from iteration 2 kStallWindow on: a halved
  // step is cheaper than the rest of max_iterations, each with a factorisation. Or (when given
  // up so) a triangle is inverted at the iterate and the residual stagnates: such iterates sit
  // near an element's collapse, where its terms (K ~ 1/A) are singular, and the step either
  // never converges or converges with the triangle inverted, which is no solution either
  // (fluid_step.cpp, check_admissible). On the elastic-obstacle dam break to 1 s, 127 of 1680
  // attempts converged inverted and 86 ran to the iteration limit; the test stops 258 attempts,
  // 13 of which would have converged admissible (they are halved instead).
  bool hopeless() const;
  // The reason of hopeless(), for the failure's message.
  bool inverted_and_stagnating() const;
  // This residual is above half the previous one.
  bool stalled() const;

 private:
  double tolerance_;
  int max_iterations_;
  bool give_up_inverted_;
  std::vector<double> residuals_, best_;  // best_: the smallest residual up to each iteration
  bool inverted_ = false;                 // at the last iterate
};

}  // namespace pfem
