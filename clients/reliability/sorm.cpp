#include "clients/reliability/sorm.h"

#include <algorithm>
#include <cmath>
#include <complex>
#include <limits>

#include "clients/reliability/parallel.h"

namespace pfem::reliability {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// Probabilities for beta >= 0.
SormProbabilities positive(double beta, const std::vector<double>& kappa) {
  const double Phi = standard_normal_cdf(-beta);
  const double phi = standard_normal_pdf(beta);
  const double psi = phi / Phi;
  double prod_b = 1.0;
  double prod_b1 = 1.0;
  double prod_psi = 1.0;
  std::complex<double> prod_i = 1.0;
  bool ok_b = true;
  bool ok_psi = true;
  for (double k : kappa) {
    const double a = 1.0 + beta * k;
    const double a1 = 1.0 + (beta + 1.0) * k;
    const double ap = 1.0 + psi * k;
    ok_b = ok_b && a > 0 && a1 > 0;
    ok_psi = ok_psi && ap > 0;
    prod_b *= 1.0 / std::sqrt(a);
    prod_b1 *= 1.0 / std::sqrt(a1);
    prod_psi *= 1.0 / std::sqrt(ap);
    prod_i *= std::pow(std::complex<double>(1.0 + beta * k, k), -0.5);
  }
  SormProbabilities p{kNaN, kNaN, kNaN};
  if (ok_b) {
    const double a1 = Phi * prod_b;
    const double t = beta * Phi - phi;
    const double a2 = t * (prod_b - prod_b1);
    const double a3 = (beta + 1.0) * t * (prod_b - prod_i.real());
    p.breitung = a1;
    // The three-term expansion can leave [0, 1] for large beta * sum(kappa); report nothing then.
    const double tvedt = a1 + a2 + a3;
    p.tvedt = tvedt > 0 && tvedt < 1 ? tvedt : kNaN;
  }
  if (ok_psi) p.hohenbichler_rackwitz = Phi * prod_psi;
  return p;
}

double generalized_beta(double pf) {
  return std::isfinite(pf) && pf > 0 && pf < 1 ? -standard_normal_quantile(pf) : kNaN;
}

}  // namespace

std::vector<FieldError> SormOptions::validate() const {
  std::vector<FieldError> errors;
  if (!(step > 0 && step < 1)) errors.push_back({"step", "must be in (0, 1)"});
  if (concurrency < 1) errors.push_back({"concurrency", "must be >= 1"});
  return errors;
}

SormProbabilities sorm_probabilities(double beta, const std::vector<double>& curvatures) {
  if (beta >= 0) return positive(beta, curvatures);
  std::vector<double> flipped(curvatures.size());
  std::transform(curvatures.begin(), curvatures.end(), flipped.begin(), [](double k) { return -k; });
  const SormProbabilities safe = positive(-beta, flipped);
  return {1.0 - safe.breitung, 1.0 - safe.hohenbichler_rackwitz, 1.0 - safe.tvedt};
}

SormResult run_sorm(const LimitState& g, const NatafTransform& transform, const FormResult& form,
                    const SormOptions& options) {
  if (auto errors = options.validate(); !errors.empty()) throw ProblemError(std::move(errors));
  SormResult r;
  const int n = transform.size();
  const double gn = form.gradient_u.norm();
  if (!(gn > 0) || form.u.size() != n) {
    r.message = "no usable FORM design point";
    return r;
  }
  // Orthonormal basis whose first column is alpha; the others span the tangent plane.
  Eigen::HouseholderQR<Eigen::MatrixXd> qr(Eigen::MatrixXd(form.alpha));
  const Eigen::MatrixXd basis = qr.householderQ() * Eigen::MatrixXd::Identity(n, n);
  const Eigen::MatrixXd tangent = basis.rightCols(n - 1);

  // The 2 (n - 1) gradients at u* +- step p_j are independent: `concurrency` at once.
  std::vector<Eigen::VectorXd> gradients(2 * static_cast<std::size_t>(n - 1));
  std::vector<int> evaluations(gradients.size());
  parallel_for(gradients.size(), options.concurrency, [&](std::size_t i) {
    const double sign = i % 2 == 0 ? 1.0 : -1.0;
    StandardSpaceFunction G(g, transform);
    G.value_and_gradient(form.u + sign * options.step * tangent.col(static_cast<int>(i / 2)),
                         gradients[i]);
    evaluations[i] = G.evaluations();
  });
  Eigen::MatrixXd hp(n, n - 1);  // H p_j
  for (int j = 0; j < n - 1; ++j) {
    hp.col(j) = (gradients[2 * j] - gradients[2 * j + 1]) / (2.0 * options.step);
  }
  Eigen::MatrixXd a = tangent.transpose() * hp / gn;
  a = 0.5 * (a + a.transpose()).eval();
  for (int e : evaluations) r.evaluations += e;
  if (!a.allFinite()) {
    r.message = "the Hessian of G is not finite at the design point";
    return r;
  }
  if (n > 1) {
    Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(a);
    for (int i = 0; i < n - 1; ++i) r.curvatures.push_back(eig.eigenvalues()(i));
  }
  const SormProbabilities p = sorm_probabilities(form.beta, r.curvatures);
  r.pf_breitung = p.breitung;
  r.pf_hohenbichler_rackwitz = p.hohenbichler_rackwitz;
  r.pf_tvedt = p.tvedt;
  r.beta_breitung = generalized_beta(p.breitung);
  r.beta_hohenbichler_rackwitz = generalized_beta(p.hohenbichler_rackwitz);
  r.beta_tvedt = generalized_beta(p.tvedt);
  r.valid = std::isfinite(p.breitung);
  if (!r.valid) {
    r.message = "1 + beta kappa <= 0 for a curvature: the asymptotic formulas do not apply";
  } else if (!std::isfinite(p.tvedt)) {
    r.message = "Tvedt's three-term formula falls outside (0, 1) here (strong curvature); use "
                "Breitung / Hohenbichler-Rackwitz with care and check by importance sampling";
  } else {
    r.message = "ok";
  }
  return r;
}

}  // namespace pfem::reliability
