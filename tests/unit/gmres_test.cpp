// GMRES with right preconditioning against a direct solve: a non-symmetric, diagonally dominant
// system converges to the requested residual; a good preconditioner needs few iterations; an
// iteration budget too small reports no convergence.
#include <gtest/gtest.h>

#include <Eigen/Dense>

#include "engine/solve/gmres.h"

namespace pfem {
namespace {

Eigen::MatrixXd test_matrix(int n) {
  Eigen::MatrixXd a = Eigen::MatrixXd::Zero(n, n);
  for (int i = 0; i < n; ++i) {
    a(i, i) = 4.0 + 0.01 * i;
    if (i + 1 < n) a(i, i + 1) = -1.3;
    if (i > 0) a(i, i - 1) = -0.7;
    a(i, (7 * i + 3) % n) += 0.2;  // a non-symmetric far coupling
  }
  return a;
}

TEST(Gmres, MatchesADirectSolve) {
  const int n = 200;
  const Eigen::MatrixXd a = test_matrix(n);
  const Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(n, -1.0, 2.0);
  const Eigen::VectorXd exact = a.partialPivLu().solve(b);
  const LinearOperator apply = [&a](const Eigen::VectorXd& x) -> Eigen::VectorXd { return a * x; };
  const LinearOperator identity = [](const Eigen::VectorXd& x) { return x; };
  Eigen::VectorXd x;
  const GmresResult r = gmres(apply, identity, b, x, 1e-12, 20, 400);  // restarts on the way
  ASSERT_TRUE(r.converged);
  EXPECT_LE(r.relative_residual, 1e-12);
  EXPECT_GT(r.iterations, 20);
  EXPECT_LT((x - exact).norm(), 1e-10 * exact.norm());

  // Preconditioned by the exact inverse of a nearby matrix (as the DDM's Newton factorisation is
  // to its Jacobian): a handful of iterations.
  Eigen::MatrixXd nearby = a;
  nearby.diagonal() *= 1.05;
  const auto lu = nearby.partialPivLu();
  const LinearOperator precondition = [&lu](const Eigen::VectorXd& v) -> Eigen::VectorXd { return lu.solve(v); };
  const GmresResult p = gmres(apply, precondition, b, x, 1e-13, 30, 60);
  ASSERT_TRUE(p.converged);
  EXPECT_LE(p.iterations, 12);
  EXPECT_LT((x - exact).norm(), 1e-11 * exact.norm());

  const GmresResult short_budget = gmres(apply, identity, b, x, 1e-12, 5, 5);
  EXPECT_FALSE(short_budget.converged);
  EXPECT_GT(short_budget.relative_residual, 1e-12);
}

}  // namespace
}  // namespace pfem
