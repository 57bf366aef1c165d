#pragma once
// Test helper: cols right-hand sides of n rows drawn uniformly from [-1, 1], reproducibly.
#include <Eigen/Core>
#include <random>

inline Eigen::MatrixXd random_rhs(long n, int cols, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Eigen::MatrixXd b(n, cols);
  for (int c = 0; c < cols; ++c)
    for (long i = 0; i < n; ++i) b(i, c) = u(rng);
  return b;
}
