#include "engine/solve/gmres.h"

#include <cmath>
#include <vector>

namespace pfem {

GmresResult gmres(const LinearOperator& a, const LinearOperator& m_inv, const Eigen::VectorXd& b,
                  Eigen::VectorXd& x, double tolerance, int restart, int max_iterations) {
  GmresResult result;
  x.setZero(b.size());
  const double b_norm = b.norm();
  if (b_norm == 0.0) return {true, 0, 0.0};
  Eigen::VectorXd r = b;
  while (result.iterations < max_iterations) {
    // Arnoldi on A M^-1 from the current residual, Givens rotations on the Hessenberg matrix.
    const double beta = r.norm();
    std::vector<Eigen::VectorXd> v{r / beta}, z;  // z[j] = M^-1 v[j], kept for the update
    Eigen::MatrixXd h = Eigen::MatrixXd::Zero(restart + 1, restart);
    Eigen::VectorXd g = Eigen::VectorXd::Zero(restart + 1), cs(restart), sn(restart);
    g(0) = beta;
    int k = 0;
    for (; k < restart && result.iterations < max_iterations; ++k, ++result.iterations) {
      z.push_back(m_inv(v[k]));
      Eigen::VectorXd w = a(z[k]);
      for (int j = 0; j <= k; ++j) {
        h(j, k) = w.dot(v[j]);
        w -= h(j, k) * v[j];
      }
      h(k + 1, k) = w.norm();
      v.push_back(w / h(k + 1, k));
      for (int j = 0; j < k; ++j) {
        const double t = cs(j) * h(j, k) + sn(j) * h(j + 1, k);
        h(j + 1, k) = -sn(j) * h(j, k) + cs(j) * h(j + 1, k);
        h(j, k) = t;
      }
      const double d = std::hypot(h(k, k), h(k + 1, k));
      cs(k) = h(k, k) / d, sn(k) = h(k + 1, k) / d;
      h(k, k) = d, h(k + 1, k) = 0.0;
      g(k + 1) = -sn(k) * g(k), g(k) *= cs(k);
      if (std::abs(g(k + 1)) <= tolerance * b_norm) {
        ++k, ++result.iterations;
        break;
      }
    }
    // x += M^-1 V y = Z y with H y = g (upper triangular k x k): no further preconditioner solve.
    const Eigen::VectorXd y = h.topLeftCorner(k, k).triangularView<Eigen::Upper>().solve(g.head(k));
    for (int j = 0; j < k; ++j) x += y(j) * z[j];
    r = b - a(x);  // the true residual, not the recursion's estimate
    result.relative_residual = r.norm() / b_norm;
    if (result.relative_residual <= tolerance) {
      result.converged = true;
      break;
    }
  }
  return result;
}

}  // namespace pfem
