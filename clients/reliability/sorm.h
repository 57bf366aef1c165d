#pragma once
// SORM at the FORM design point: the principal curvatures kappa_i of the limit-state surface
// in standard normal space (the Hessian of G projected on the tangent plane and divided by
// ||grad G||, built from central finite differences of exact gradients along an orthonormal
// basis of the tangent plane; the 2 (n - 1) gradients are evaluated `concurrency` at a time), then
//   Breitung (1984):               pf = Phi(-beta) prod (1 + beta kappa_i)^-1/2
//   Hohenbichler & Rackwitz (1988): pf = Phi(-beta) prod (1 + psi kappa_i)^-1/2,
//                                   psi = phi(beta) / Phi(-beta)
//   Tvedt (1990), three terms:     A1 + A2 + A3.
// Sign convention: kappa > 0 when the surface curves away from the origin (the failure
// domain is smaller than FORM's half-space). For beta < 0 the formulas are applied to the
// safe domain and pf = 1 - p_safe.
#include <string>
#include <vector>

#include "clients/reliability/errors.h"
#include "clients/reliability/form.h"
#include "clients/reliability/limit_state.h"
#include "clients/reliability/nataf.h"

namespace pfem::reliability {

struct SormOptions {
  double step = 1e-4;  // u-space step of the central differences of the gradient
  int concurrency = 1; // gradients evaluated at once
  std::vector<FieldError> validate() const;
};

struct SormResult {
  bool valid = false;            // false when Breitung is singular (1 + beta kappa <= 0)
  std::string message;
  std::vector<double> curvatures;  // ascending
  double pf_breitung = 0.0;
  double beta_breitung = 0.0;      // -Phi^-1(pf)
  double pf_hohenbichler_rackwitz = 0.0;
  double beta_hohenbichler_rackwitz = 0.0;
  double pf_tvedt = 0.0;
  double beta_tvedt = 0.0;
  int evaluations = 0;             // calls of g
};

// Breitung, Hohenbichler-Rackwitz and Tvedt from beta and the curvatures alone (NaN where
// singular, and Tvedt NaN where its three terms leave (0, 1)).
struct SormProbabilities {
  double breitung;
  double hohenbichler_rackwitz;
  double tvedt;
};
SormProbabilities sorm_probabilities(double beta, const std::vector<double>& curvatures);

// Throws ProblemError for invalid options.
SormResult run_sorm(const LimitState& g, const NatafTransform& transform, const FormResult& form,
                    const SormOptions& options = {});

}  // namespace pfem::reliability
