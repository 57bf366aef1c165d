#include "engine/solve/newton_monitor.h"

#include <algorithm>

namespace pfem {

void NewtonMonitor::record(double residual) {
  best_.push_back(best_.empty() ? residual : std::min(best_.back(), residual));
  residuals_.push_back(residual);
}

bool NewtonMonitor::hopeless() const {
  const int it = iteration();
  return it >= 2 * kStallWindow && best_[it] > 0.5 * best_[it - kStallWindow];
}

bool NewtonMonitor::stalled() const {
  const int it = iteration();
  return it > 0 && residuals_[it] > 0.5 * residuals_[it - 1];
}

}  // namespace pfem
