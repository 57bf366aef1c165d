#pragma once
// Bilinear elastoplastic material with linear kinematic hardening (rate-independent 1D
// plasticity, backward-Euler return mapping).
//
//   yield function   f = |sigma - alpha| - Fy
//   elastic modulus  E0, plastic modulus H = b E0 / (1 - b), so that the elastoplastic
//   slope is E0 H / (E0 + H) = b E0 (b = hardening ratio in [0, 1); b = 0 is perfectly plastic)
//   history          plastic strain eps_p and back stress alpha, committed once per step.
//
// The return map is a pure function of (parameters, committed history, strain) so that the
// DDM can differentiate it later: dsigma/dtheta|eps and the history sensitivities
// (deps_p/dtheta, dalpha/dtheta) live beside BilinearHistory without reshaping the class.
#include "engine/structure/uniaxial_material.h"

namespace pfem::structure {

struct BilinearParameters {
  double fy = 0.0;  // yield stress, > 0
  double e0 = 0.0;  // initial elastic modulus, > 0
  double b = 0.0;   // hardening ratio, in [0, 1)
};

// Path-dependent state (what commit() stores).
struct BilinearHistory {
  double plastic_strain = 0.0;
  double back_stress = 0.0;
};

struct BilinearResponse {
  double stress = 0.0;
  double tangent = 0.0;     // consistent (algorithmic) tangent
  BilinearHistory history;  // trial history after the return map
  bool plastic = false;     // whether the step is a plastic one
};

// Return map from the committed history to the total strain `strain`.
BilinearResponse bilinear_return_map(const BilinearParameters& p, const BilinearHistory& committed,
                                     double strain);

class BilinearMaterial final : public UniaxialMaterial {
 public:
  // Throws std::invalid_argument: fields "fy" (> 0), "e0" (> 0), "hardening_ratio" ([0, 1)).
  BilinearMaterial(double fy, double e0, double b);

  void set_trial_strain(double strain) override;
  double strain() const override { return strain_; }
  double stress() const override { return trial_.stress; }
  double tangent() const override { return trial_.tangent; }
  double initial_tangent() const override { return params_.e0; }

  void commit() override;
  void revert_to_last_commit() override;
  std::unique_ptr<UniaxialMaterial> clone() const override;

  const BilinearParameters& parameters() const { return params_; }
  const BilinearHistory& committed_history() const { return committed_; }
  const BilinearHistory& trial_history() const { return trial_.history; }
  bool is_plastic() const { return trial_.plastic; }

 private:
  BilinearParameters params_;
  BilinearHistory committed_;
  double committed_strain_ = 0.0;
  double strain_ = 0.0;
  BilinearResponse trial_;
};

}  // namespace pfem::structure
