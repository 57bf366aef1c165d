#include "engine/structure/bilinear_material.h"

#include <cmath>

#include "engine/structure/validation.h"

namespace pfem::structure {

BilinearResponse bilinear_return_map(const BilinearParameters& p, const BilinearHistory& committed,
                                     double strain) {
  const double E = p.e0;
  const double H = p.b * E / (1.0 - p.b);
  BilinearResponse r;
  const double trial_stress = E * (strain - committed.plastic_strain);
  const double xi = trial_stress - committed.back_stress;
  const double f = std::abs(xi) - p.fy;
  if (f <= 0.0) {
    r.stress = trial_stress;
    r.tangent = E;
    r.history = committed;
    return r;
  }
  const double sign = xi > 0.0 ? 1.0 : -1.0;
  const double dgamma = f / (E + H);
  r.plastic = true;
  r.stress = trial_stress - E * dgamma * sign;
  r.tangent = E * H / (E + H);  // = b E0; the linear-hardening return map is exact
  r.history.plastic_strain = committed.plastic_strain + dgamma * sign;
  r.history.back_stress = committed.back_stress + H * dgamma * sign;
  return r;
}

BilinearMaterial::BilinearMaterial(double fy, double e0, double b) : params_{fy, e0, b} {
  require_positive(fy, "fy");
  require_positive(e0, "e0");
  if (!(b >= 0.0 && b < 1.0))
    throw_invalid("hardening_ratio", "must be in [0, 1) (got " + std::to_string(b) + ")");
  trial_.tangent = e0;
}

void BilinearMaterial::set_trial_strain(double strain) {
  strain_ = strain;
  trial_ = bilinear_return_map(params_, committed_, strain);
}

void BilinearMaterial::commit() {
  committed_ = trial_.history;
  committed_strain_ = strain_;
}

void BilinearMaterial::revert_to_last_commit() { set_trial_strain(committed_strain_); }

std::unique_ptr<UniaxialMaterial> BilinearMaterial::clone() const {
  return std::make_unique<BilinearMaterial>(*this);
}

}  // namespace pfem::structure
