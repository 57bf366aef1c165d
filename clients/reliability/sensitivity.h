#pragma once
// Sensitivities of the FORM reliability index to the distribution parameters, from the
// standard result (Hohenbichler & Rackwitz 1986; Bjerager & Krenk 1989)
//   d beta / d theta = alpha^T (d u / d theta) at fixed x = x*,
// where u = T(x; theta) is the Nataf transformation and theta the mean or standard deviation
// of one variable. The limit state is not evaluated again: du/dtheta is a central difference
// of the transform alone (the marginal rebuilt with the perturbed moment, its fictive
// correlations solved again). d pf / d theta = -phi(beta) d beta / d theta.
#include <vector>

#include "clients/reliability/form.h"
#include "clients/reliability/nataf.h"

namespace pfem::reliability {

struct MomentSensitivity {
  double dbeta_dmean = 0.0;
  double dbeta_dstddev = 0.0;
  double dpf_dmean = 0.0;
  double dpf_dstddev = 0.0;
};

// One entry per variable. `relative_step` scales the central-difference step by the
// variable's standard deviation. Variables whose moments cannot be perturbed (e.g. a Fréchet
// without finite variance) get NaN.
std::vector<MomentSensitivity> beta_sensitivities(const NatafTransform& transform,
                                                  const FormResult& form,
                                                  double relative_step = 1e-5);

}  // namespace pfem::reliability
