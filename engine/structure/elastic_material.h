#pragma once
// Linear elastic uniaxial material: stress = E * strain. DDM seed: dE/dtheta_k.
#include "engine/structure/seeds.h"
#include "engine/structure/uniaxial_material.h"

namespace pfem::structure {

class ElasticMaterial final : public UniaxialMaterial {
 public:
  // Throws std::invalid_argument unless E > 0 (field "e").
  explicit ElasticMaterial(double E);

  void set_trial_strain(double strain) override { strain_ = strain; }
  double strain() const override { return strain_; }
  double stress() const override { return E_ * strain_; }
  double tangent() const override { return E_; }
  double initial_tangent() const override { return E_; }

  void commit() override { committed_strain_ = strain_; }
  void revert_to_last_commit() override { strain_ = committed_strain_; }
  std::unique_ptr<UniaxialMaterial> clone() const override;
  void archive(StateArchive& a) override;

  double youngs_modulus() const { return E_; }

  // --- DDM ---
  void set_modulus_seed(int k, double dE) { seeds_.set(k, dE); }
  double conditional_stress_sensitivity(int k) const override { return seeds_[k] * strain_; }
  double initial_tangent_sensitivity(int k) const override { return seeds_[k]; }

 protected:
  void update_history_sensitivity(int, double) override {}  // no history

 private:
  double E_;
  double strain_ = 0.0;
  double committed_strain_ = 0.0;
  Seeds<double> seeds_;
};

}  // namespace pfem::structure
