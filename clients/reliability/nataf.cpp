#include "clients/reliability/nataf.h"

#include <cmath>
#include <cstdint>
#include <sstream>

#include <boost/math/tools/roots.hpp>

namespace pfem::reliability {

namespace {

// The default rule is built once (thread-safe static initialisation, immutable after);
// other sizes are built on demand.
GaussHermiteRule rule(int n) {
  static const GaussHermiteRule r48 = gauss_hermite_rule(48);
  return n == 48 ? r48 : gauss_hermite_rule(n);
}

std::string format_range(double lo, double hi) {
  std::ostringstream out;
  out.precision(4);
  out << "[" << lo << ", " << hi << "]";
  return out.str();
}

}  // namespace

GaussHermiteRule gauss_hermite_rule(int n) {
  // Jacobi matrix of the probabilists' Hermite polynomials: off-diagonal sqrt(k).
  Eigen::MatrixXd jacobi = Eigen::MatrixXd::Zero(n, n);
  for (int k = 1; k < n; ++k) {
    jacobi(k, k - 1) = jacobi(k - 1, k) = std::sqrt(static_cast<double>(k));
  }
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(jacobi);
  GaussHermiteRule out;
  out.nodes.resize(n);
  out.weights.resize(n);
  for (int k = 0; k < n; ++k) {
    out.nodes[k] = eig.eigenvalues()(k);
    const double v = eig.eigenvectors()(0, k);
    out.weights[k] = v * v;
  }
  return out;
}

double nataf_correlation(const Distribution& a, const Distribution& b, double rho0, int nodes) {
  const GaussHermiteRule gh = rule(nodes);
  const int n = static_cast<int>(gh.nodes.size());
  // Moments by the same rule, so that quadrature errors cancel (exact for normal pairs).
  std::vector<double> xa(n);
  std::vector<double> xb(n);
  double ma = 0.0;
  double mb = 0.0;
  for (int k = 0; k < n; ++k) {
    xa[k] = a.from_standard_normal(gh.nodes[k]);
    xb[k] = b.from_standard_normal(gh.nodes[k]);
    ma += gh.weights[k] * xa[k];
    mb += gh.weights[k] * xb[k];
  }
  double va = 0.0;
  double vb = 0.0;
  for (int k = 0; k < n; ++k) {
    va += gh.weights[k] * (xa[k] - ma) * (xa[k] - ma);
    vb += gh.weights[k] * (xb[k] - mb) * (xb[k] - mb);
  }
  const double s = std::sqrt(std::max(0.0, 1.0 - rho0 * rho0));
  double cov = 0.0;
  for (int k = 0; k < n; ++k) {
    double inner = 0.0;
    for (int l = 0; l < n; ++l) {
      inner += gh.weights[l] * (b.from_standard_normal(rho0 * gh.nodes[k] + s * gh.nodes[l]) - mb);
    }
    cov += gh.weights[k] * (xa[k] - ma) * inner;
  }
  return cov / std::sqrt(va * vb);
}

double fictive_correlation(const Distribution& a, const Distribution& b, double rho, int nodes) {
  if (rho == 0.0) return 0.0;
  if (a.kind() == DistributionKind::kNormal && b.kind() == DistributionKind::kNormal) return rho;
  if (!std::isfinite(a.stddev()) || !std::isfinite(b.stddev())) {
    throw NatafError(-1, -1, "a variable without finite variance cannot be correlated");
  }
  const double lo = nataf_correlation(a, b, -1.0, nodes);
  const double hi = nataf_correlation(a, b, 1.0, nodes);
  if (!(rho > lo && rho < hi)) {
    throw NatafError(-1, -1,
                     "this pair of distributions can only reach correlations in " +
                         format_range(lo, hi));
  }
  auto f = [&](double r0) { return nataf_correlation(a, b, r0, nodes) - rho; };
  std::uintmax_t iterations = 100;
  const auto r = boost::math::tools::toms748_solve(f, -1.0, 1.0, lo - rho, hi - rho,
                                                   boost::math::tools::eps_tolerance<double>(48),
                                                   iterations);
  return 0.5 * (r.first + r.second);
}

NatafTransform::NatafTransform(std::vector<Distribution> marginals, Eigen::MatrixXd correlation)
    : marginals_(std::move(marginals)), correlation_(std::move(correlation)) {
  const int n = size();
  if (correlation_.size() == 0) correlation_ = Eigen::MatrixXd::Identity(n, n);
  if (correlation_.rows() != n || correlation_.cols() != n) {
    throw NatafError(-1, -1, "the correlation matrix does not match the number of variables");
  }
  Eigen::LLT<Eigen::MatrixXd> llt(correlation_);
  if (llt.info() != Eigen::Success || (llt.matrixL().toDenseMatrix().diagonal().array() <= 1e-10).any()) {
    throw NatafError(-1, -1, "the correlation matrix is not positive definite");
  }
  fictive_ = Eigen::MatrixXd::Identity(n, n);
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < i; ++j) {
      if (correlation_(i, j) == 0.0) continue;
      try {
        fictive_(i, j) = fictive_(j, i) =
            reliability::fictive_correlation(marginals_[i], marginals_[j], correlation_(i, j));
      } catch (const NatafError& e) {
        throw NatafError(j, i, e.what());
      }
    }
  }
  factorise();
}

NatafTransform::NatafTransform(std::vector<Distribution> marginals, Eigen::MatrixXd correlation,
                               Eigen::MatrixXd fictive)
    : marginals_(std::move(marginals)),
      correlation_(std::move(correlation)),
      fictive_(std::move(fictive)) {
  factorise();
}

void NatafTransform::factorise() {
  Eigen::LLT<Eigen::MatrixXd> llt(fictive_);
  if (llt.info() != Eigen::Success) {
    throw NatafError(-1, -1,
                     "the fictive correlation matrix of the Nataf transformation is not "
                     "positive definite");
  }
  lower_ = llt.matrixL();
}

NatafTransform NatafTransform::with_marginal(int i, const Distribution& marginal) const {
  std::vector<Distribution> marginals = marginals_;
  marginals[i] = marginal;
  Eigen::MatrixXd fictive = fictive_;
  for (int j = 0; j < size(); ++j) {
    if (j == i || correlation_(i, j) == 0.0) continue;
    fictive(i, j) = fictive(j, i) =
        reliability::fictive_correlation(marginals[i], marginals[j], correlation_(i, j));
  }
  return NatafTransform(std::move(marginals), correlation_, std::move(fictive));
}

Eigen::VectorXd NatafTransform::to_u(const Eigen::VectorXd& x) const {
  Eigen::VectorXd z(size());
  for (int i = 0; i < size(); ++i) z(i) = marginals_[i].to_standard_normal(x(i));
  return lower_.triangularView<Eigen::Lower>().solve(z);
}

Eigen::VectorXd NatafTransform::to_x(const Eigen::VectorXd& u) const {
  const Eigen::VectorXd z = lower_.triangularView<Eigen::Lower>() * u;
  Eigen::VectorXd x(size());
  for (int i = 0; i < size(); ++i) x(i) = marginals_[i].from_standard_normal(z(i));
  return x;
}

Eigen::VectorXd NatafTransform::to_x(const Eigen::VectorXd& u, Eigen::MatrixXd& jacobian) const {
  const Eigen::VectorXd z = lower_.triangularView<Eigen::Lower>() * u;
  Eigen::VectorXd x(size());
  Eigen::VectorXd dxdz(size());
  for (int i = 0; i < size(); ++i) {
    x(i) = marginals_[i].from_standard_normal(z(i));
    const double f = marginals_[i].pdf(x(i));
    dxdz(i) = (f > 0 && std::isfinite(f)) ? standard_normal_pdf(z(i)) / f : 0.0;
  }
  jacobian = dxdz.asDiagonal() * lower_;
  return x;
}

}  // namespace pfem::reliability
