#pragma once
// Central finite differences, the reference every analytic derivative of this library is
// tested against (tangents now, DDM conditional derivatives later).
#include <Eigen/Core>

namespace pfem::structure {

// J(:, j) = (f(x + h e_j) - f(x - h e_j)) / (2 h); f maps Eigen::VectorXd -> Eigen::VectorXd.
// f may have side effects (e.g. set a trial state); it is called 2 n times.
template <typename F>
Eigen::MatrixXd central_difference_jacobian(F&& f, const Eigen::VectorXd& x, double h) {
  Eigen::MatrixXd J;
  for (Eigen::Index j = 0; j < x.size(); ++j) {
    Eigen::VectorXd xp = x, xm = x;
    xp(j) += h;
    xm(j) -= h;
    const Eigen::VectorXd column = (f(xp) - f(xm)) / (2.0 * h);
    if (j == 0) J.resize(column.size(), x.size());
    J.col(j) = column;
  }
  return J;
}

}  // namespace pfem::structure
