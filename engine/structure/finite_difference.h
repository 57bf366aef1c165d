#pragma once
// Central finite differences, the reference every analytic derivative of this library is
// tested against (tangents, DDM conditional derivatives, whole-run sensitivities).
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

// (f(theta + h) - f(theta - h)) / (2 h) for f: double -> double or a fixed Eigen type.
template <typename F>
auto central_difference(F&& f, double theta, double h) {
  const auto plus = f(theta + h);
  const auto minus = f(theta - h);
  return decltype(plus)((plus - minus) / (2.0 * h));
}

// Entrywise error of `a` against the reference `b`: max |a_i - b_i| / max(|b_i|, floor max|b|),
// so that entries far below the largest are measured against floor times the largest (an
// all-zero reference gives the absolute error).
inline double max_relative_error(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b,
                                 double floor = 1e-3) {
  const double scale = b.cwiseAbs().maxCoeff();
  if (scale == 0.0) return a.cwiseAbs().maxCoeff();
  return ((a - b).array().abs() / b.array().abs().max(floor * scale)).maxCoeff();
}

}  // namespace pfem::structure
