#include "clients/reliability/sensitivity.h"

#include <cmath>
#include <limits>
#include <stdexcept>

namespace pfem::reliability {

std::vector<MomentSensitivity> beta_sensitivities(const NatafTransform& transform,
                                                  const FormResult& form, double relative_step) {
  const int n = transform.size();
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double phi = standard_normal_pdf(form.beta);
  std::vector<MomentSensitivity> out(n);
  for (int i = 0; i < n; ++i) {
    const Distribution& d = transform.marginals()[i];
    const double mean = d.mean();
    const double sd = d.stddev();
    const double h = relative_step * sd;
    // d beta / d theta for theta = mean (k = 0) or stddev (k = 1).
    auto derivative = [&](int k) {
      try {
        const double dm = k == 0 ? h : 0.0;
        const double ds = k == 1 ? h : 0.0;
        const NatafTransform plus = transform.with_marginal(i, d.with_moments(mean + dm, sd + ds));
        const NatafTransform minus = transform.with_marginal(i, d.with_moments(mean - dm, sd - ds));
        const Eigen::VectorXd du = (plus.to_u(form.x) - minus.to_u(form.x)) / (2.0 * h);
        return form.alpha.dot(du);
      } catch (const std::exception&) {
        return nan;
      }
    };
    if (!(std::isfinite(mean) && std::isfinite(sd) && sd > 0)) {
      out[i] = {nan, nan, nan, nan};
      continue;
    }
    out[i].dbeta_dmean = derivative(0);
    out[i].dbeta_dstddev = derivative(1);
    out[i].dpf_dmean = -phi * out[i].dbeta_dmean;
    out[i].dpf_dstddev = -phi * out[i].dbeta_dstddev;
  }
  return out;
}

}  // namespace pfem::reliability
