#pragma once
// Gauss-Legendre points and weights mapped to [0, 1] (weights sum to 1), ascending.
#include <vector>

namespace pfem::structure {

struct QuadratureRule {
  std::vector<double> points;   // in (0, 1)
  std::vector<double> weights;  // sum = 1
};

// n >= 1; exact for polynomials of degree 2n - 1.
QuadratureRule gauss_legendre_01(int n);

}  // namespace pfem::structure
