#include "engine/structure/bilinear_material.h"

#include <cmath>

#include "engine/structure/validation.h"

namespace pfem::structure {

namespace {
double plastic_modulus(const BilinearParameters& p) { return p.b * p.e0 / (1.0 - p.b); }
}  // namespace

BilinearResponse bilinear_return_map(const BilinearParameters& p, const BilinearHistory& committed,
                                     double strain) {
  const double E = p.e0;
  const double H = plastic_modulus(p);
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

BilinearSensitivity bilinear_return_map_sensitivity(const BilinearParameters& p,
                                                    const BilinearParameters& dp,
                                                    const BilinearHistory& committed,
                                                    const BilinearHistory& dcommitted,
                                                    double strain, double dstrain) {
  const double E = p.e0, dE = dp.e0;
  const double H = plastic_modulus(p);
  const double dH = (p.b * dE + E * dp.b / (1.0 - p.b)) / (1.0 - p.b);
  const double trial_stress = E * (strain - committed.plastic_strain);
  const double dtrial_stress =
      dE * (strain - committed.plastic_strain) + E * (dstrain - dcommitted.plastic_strain);
  const double xi = trial_stress - committed.back_stress;
  const double f = std::abs(xi) - p.fy;
  BilinearSensitivity d{dtrial_stress, dcommitted};
  if (f <= 0.0) return d;  // elastic: the history does not move
  const double sign = xi > 0.0 ? 1.0 : -1.0;
  const double dgamma = f / (E + H);
  const double df = sign * (dtrial_stress - dcommitted.back_stress) - dp.fy;
  const double d_dgamma = (df - dgamma * (dE + dH)) / (E + H);
  d.stress -= (dE * dgamma + E * d_dgamma) * sign;
  d.history.plastic_strain += d_dgamma * sign;
  d.history.back_stress += (dH * dgamma + H * d_dgamma) * sign;
  return d;
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
  committed_sens_ = trial_sens_;
}

void BilinearMaterial::revert_to_last_commit() {
  set_trial_strain(committed_strain_);
  trial_sens_ = committed_sens_;
}

void BilinearMaterial::set_num_parameters(int P) {
  UniaxialMaterial::set_num_parameters(P);
  committed_sens_.assign(P, BilinearHistory{});
  trial_sens_ = committed_sens_;
}

BilinearSensitivity BilinearMaterial::sensitivity(int k, double dstrain) const {
  return bilinear_return_map_sensitivity(params_, seeds_[k], committed_, committed_sens_.at(k),
                                         strain_, dstrain);
}

double BilinearMaterial::conditional_stress_sensitivity(int k) const {
  return sensitivity(k, 0.0).stress;
}

void BilinearMaterial::update_history_sensitivity(int k, double dstrain) {
  trial_sens_.at(k) = sensitivity(k, dstrain).history;
}

std::unique_ptr<UniaxialMaterial> BilinearMaterial::clone() const {
  return std::make_unique<BilinearMaterial>(*this);
}

void BilinearMaterial::archive(StateArchive& a) {
  UniaxialMaterial::archive(a);
  const auto history = [&](BilinearHistory& h) { a(h.plastic_strain), a(h.back_stress); };
  history(committed_);
  a(committed_strain_), a(strain_);
  a(trial_.stress), a(trial_.tangent), a(trial_.plastic);
  history(trial_.history);
  a.expect(committed_sens_.size(), "parameters of a material");
  for (auto& h : committed_sens_) history(h);
  for (auto& h : trial_sens_) history(h);
}

}  // namespace pfem::structure
