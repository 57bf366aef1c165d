#include "engine/structure/gauss_legendre.h"

#include <cmath>
#include <numbers>

namespace pfem::structure {

QuadratureRule gauss_legendre_01(int n) {
  QuadratureRule rule;
  rule.points.resize(n);
  rule.weights.resize(n);
  for (int i = 0; i < n; ++i) {
    // Newton iteration on P_n from the usual asymptotic guess (descending roots on [-1, 1]).
    double x = std::cos(std::numbers::pi * (i + 0.75) / (n + 0.5));
    double dp = 1.0;
    for (int iter = 0; iter < 100; ++iter) {
      double p0 = 1.0, p1 = x;
      for (int k = 2; k <= n; ++k) {
        const double p2 = ((2.0 * k - 1.0) * x * p1 - (k - 1.0) * p0) / k;
        p0 = p1;
        p1 = p2;
      }
      dp = n * (x * p1 - p0) / (x * x - 1.0);
      const double dx = p1 / dp;
      x -= dx;
      if (std::abs(dx) < 1e-16) break;
    }
    // Recompute the derivative at the converged root for the weight.
    double p0 = 1.0, p1 = x;
    for (int k = 2; k <= n; ++k) {
      const double p2 = ((2.0 * k - 1.0) * x * p1 - (k - 1.0) * p0) / k;
      p0 = p1;
      p1 = p2;
    }
    dp = n * (x * p1 - p0) / (x * x - 1.0);
    const int j = n - 1 - i;  // ascending order
    rule.points[j] = 0.5 * (1.0 + x);
    rule.weights[j] = 1.0 / ((1.0 - x * x) * dp * dp);  // 2/((1-x^2) P'^2) halved for [0, 1]
  }
  return rule;
}

}  // namespace pfem::structure
