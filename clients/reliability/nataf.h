#pragma once
// The Nataf transformation between the basic variables x (with their marginals and
// correlation matrix R) and independent standard normal variables u:
//   z_i = Phi^-1(F_i(x_i)),   u = L^-1 z,   R0 = L L^T,
// where R0 holds the fictive correlations of the z's, each solved numerically from
//   rho_ij = E[(x_i - mu_i)(x_j - mu_j)] / (sigma_i sigma_j)
// by a 2-D Gauss-Hermite quadrature (z_j = rho0 z_i + sqrt(1 - rho0^2) w) and a
// TOMS 748 root solve on rho0 in [-1, 1].
//
// A NatafTransform is immutable after construction and safe to share between threads.
#include <stdexcept>
#include <string>
#include <vector>

#include <Eigen/Dense>

#include "clients/reliability/distributions.h"

namespace pfem::reliability {

// Why a transform could not be built. `i`, `j` name the offending pair (both -1 when the
// problem is the matrix as a whole).
class NatafError : public std::runtime_error {
 public:
  NatafError(int i, int j, const std::string& message)
      : std::runtime_error(message), i_(i), j_(j) {}
  int i() const { return i_; }
  int j() const { return j_; }

 private:
  int i_;
  int j_;
};

// Correlation of (x_a, x_b) when their standard normals have correlation rho0
// (the quadrature above, with `nodes` Gauss-Hermite points per dimension).
double nataf_correlation(const Distribution& a, const Distribution& b, double rho0,
                         int nodes = 48);

// The fictive correlation rho0 that gives corr(x_a, x_b) = rho. Exact (rho0 = rho) for two
// normal variables. Throws NatafError(-1, -1, ...) when rho lies outside the range
// [nataf_correlation(-1), nataf_correlation(1)] that the pair can reach, or when a marginal
// has no finite variance.
double fictive_correlation(const Distribution& a, const Distribution& b, double rho,
                           int nodes = 48);

// Probabilists' Gauss-Hermite rule (weight exp(-z^2/2)/sqrt(2 pi), weights sum to 1), by the
// Golub-Welsch eigenvalue method.
struct GaussHermiteRule {
  std::vector<double> nodes;
  std::vector<double> weights;
};
GaussHermiteRule gauss_hermite_rule(int n);

class NatafTransform {
 public:
  // `correlation` is R (symmetric, unit diagonal); an empty matrix means independent.
  // Throws NatafError: (-1, -1) when R or R0 is not positive definite, (i, j) when a pair's
  // correlation cannot be reached.
  NatafTransform(std::vector<Distribution> marginals, Eigen::MatrixXd correlation = {});

  int size() const { return static_cast<int>(marginals_.size()); }
  const std::vector<Distribution>& marginals() const { return marginals_; }
  const Eigen::MatrixXd& correlation() const { return correlation_; }          // R
  const Eigen::MatrixXd& fictive_correlation() const { return fictive_; }      // R0
  const Eigen::MatrixXd& cholesky() const { return lower_; }                   // L

  Eigen::VectorXd to_u(const Eigen::VectorXd& x) const;
  Eigen::VectorXd to_x(const Eigen::VectorXd& u) const;
  // x(u) and J = dx/du = diag(phi(z_i) / f_i(x_i)) L at u.
  Eigen::VectorXd to_x(const Eigen::VectorXd& u, Eigen::MatrixXd& jacobian) const;

  // A transform with marginal i replaced (the fictive correlations of row/column i are
  // solved again, the others kept).
  NatafTransform with_marginal(int i, const Distribution& marginal) const;

 private:
  NatafTransform(std::vector<Distribution> marginals, Eigen::MatrixXd correlation,
                 Eigen::MatrixXd fictive);
  void factorise();

  std::vector<Distribution> marginals_;
  Eigen::MatrixXd correlation_;
  Eigen::MatrixXd fictive_;
  Eigen::MatrixXd lower_;
};

}  // namespace pfem::reliability
