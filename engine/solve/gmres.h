#pragma once
// Restarted GMRES with right preconditioning, for the DDM's small right-hand-side counts: the
// exact Jacobian of a step differs from the response's factorised Newton matrix only by the
// geometric terms and the iterate's drift, so a few iterations preconditioned by that
// factorisation replace a full LU of the Jacobian.
#include <Eigen/Core>
#include <functional>

namespace pfem {

using LinearOperator = std::function<Eigen::VectorXd(const Eigen::VectorXd&)>;

struct GmresResult {
  bool converged = false;
  int iterations = 0;
  double relative_residual = 0.0;  // ||b - A x|| / ||b||
};

// Solves A x = b from x = 0 with the preconditioner M^-1 applied on the right.
GmresResult gmres(const LinearOperator& a, const LinearOperator& m_inv, const Eigen::VectorXd& b,
                  Eigen::VectorXd& x, double tolerance, int restart, int max_iterations);

}  // namespace pfem
