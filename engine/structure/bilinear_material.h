#pragma once
// Bilinear elastoplastic material with linear kinematic hardening (rate-independent 1D
// plasticity, backward-Euler return mapping).
//
//   yield function   f = |sigma - alpha| - Fy
//   elastic modulus  E0, plastic modulus H = b E0 / (1 - b), so that the elastoplastic
//   slope is E0 H / (E0 + H) = b E0 (b = hardening ratio in [0, 1); b = 0 is perfectly plastic)
//   history          plastic strain eps_p and back stress alpha, committed once per step.
//
// The return map is a pure function of (parameters, committed history, strain); the DDM
// differentiates it (bilinear_return_map_sensitivity) with the plastic/elastic branch and the
// sign of the return held fixed. Seeds: d(fy, e0, b)/dtheta_k as a BilinearParameters.
#include <vector>

#include "engine/structure/seeds.h"
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

// Derivative of bilinear_return_map w.r.t. one parameter: the seeds dp, the committed history
// sensitivity dcommitted and the strain sensitivity dstrain in, d(stress) and the trial
// history sensitivity out. Linear in (dp, dcommitted, dstrain); d(stress)/d(dstrain) is the
// consistent tangent.
struct BilinearSensitivity {
  double stress = 0.0;
  BilinearHistory history;
};
BilinearSensitivity bilinear_return_map_sensitivity(const BilinearParameters& p,
                                                    const BilinearParameters& dp,
                                                    const BilinearHistory& committed,
                                                    const BilinearHistory& dcommitted,
                                                    double strain, double dstrain);

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
  void archive(StateArchive& a) override;

  const BilinearParameters& parameters() const { return params_; }
  const BilinearHistory& committed_history() const { return committed_; }
  const BilinearHistory& trial_history() const { return trial_.history; }
  bool is_plastic() const { return trial_.plastic; }

  // --- DDM ---
  void set_parameter_seed(int k, const BilinearParameters& d) { seeds_.set(k, d); }
  void set_num_parameters(int P) override;
  double conditional_stress_sensitivity(int k) const override;
  double initial_tangent_sensitivity(int k) const override { return seeds_[k].e0; }
  // d(eps_p, alpha)/dtheta_k, committed and trial (after set_strain_sensitivity).
  const BilinearHistory& committed_history_sensitivity(int k) const {
    return committed_sens_.at(k);
  }
  const BilinearHistory& trial_history_sensitivity(int k) const { return trial_sens_.at(k); }

 protected:
  void update_history_sensitivity(int k, double dstrain) override;

 private:
  BilinearSensitivity sensitivity(int k, double dstrain) const;

  BilinearParameters params_;
  BilinearHistory committed_;
  double committed_strain_ = 0.0;
  double strain_ = 0.0;
  BilinearResponse trial_;
  Seeds<BilinearParameters> seeds_;
  std::vector<BilinearHistory> committed_sens_;  // per parameter
  std::vector<BilinearHistory> trial_sens_;
};

}  // namespace pfem::structure
