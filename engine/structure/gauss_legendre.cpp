#include "engine/structure/gauss_legendre.h"

#include <cmath>
#include <numbers>
#include <utility>

namespace pfem::structure {

namespace {
// P_n(x) and P_n'(x) by the three-term recurrence (|x| < 1).
std::pair<double, double> legendre(int n, double x) {
  double p0 = 1.0, p1 = x;
  for (int k = 2; k <= n; ++k) {
    const double p2 = ((2.0 * k - 1.0) * x * p1 - (k - 1.0) * p0) / k;
    p0 = p1;
    p1 = p2;
  }
  return {p1, n * (x * p1 - p0) / (x * x - 1.0)};
}
}  // namespace

QuadratureRule gauss_legendre_01(int n) {
  QuadratureRule rule;
  rule.points.resize(n);
  rule.weights.resize(n);
  for (int i = 0; i < n; ++i) {
    // Newton iteration on P_n from the usual asymptotic guess (descending roots on [-1, 1]).
    double x = std::cos(std::numbers::pi * (i + 0.75) / (n + 0.5));
    for (int iter = 0; iter < 100; ++iter) {
      const auto [p, dp] = legendre(n, x);
      const double dx = p / dp;
      x -= dx;
      if (std::abs(dx) < 1e-16) break;
    }
    const double dp = legendre(n, x).second;  // at the converged root, for the weight
    const int j = n - 1 - i;                    // ascending order
    rule.points[j] = 0.5 * (1.0 + x);
    rule.weights[j] = 1.0 / ((1.0 - x * x) * dp * dp);  // 2/((1-x^2) P'^2) halved for [0, 1]
  }
  return rule;
}

}  // namespace pfem::structure
