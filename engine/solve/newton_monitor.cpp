#include "engine/solve/newton_monitor.h"

#include <algorithm>

namespace pfem {

void NewtonMonitor::record(double residual, bool inverted) {
  best_.push_back(best_.empty() ? residual : std::min(best_.back(), residual));
  residuals_.push_back(residual);
  inverted_ = inverted;
}

bool NewtonMonitor::inverted_and_stagnating() const {
  const int it = iteration();
  return give_up_inverted_ && inverted_ && it >= kInvertedFrom &&
         best_[it] * kInvertedDrop > best_[it - kInvertedWindow];
}

bool NewtonMonitor::hopeless() const {
  const int it = iteration();
  return (it >= 2 * kStallWindow && best_[it] > 0.5 * best_[it - kStallWindow]) || inverted_and_stagnating();
}

bool NewtonMonitor::stalled() const {
  const int it = iteration();
  return it > 0 && residuals_[it] > 0.5 * residuals_[it - 1];
}

}  // namespace pfem
