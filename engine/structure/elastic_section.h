#pragma once
// Linear elastic section: N = EA eps0, M = EI kappa. DDM seeds: d(E, A, I)/dtheta_k, held
// in an ElasticSectionProperties.
#include "engine/structure/section.h"
#include "engine/structure/seeds.h"

namespace pfem::structure {

struct ElasticSectionProperties {
  double E = 0.0;  // Young's modulus, > 0   (field "e")
  double A = 0.0;  // area, > 0              (field "a")
  double I = 0.0;  // second moment, > 0     (field "i")
};

// Throws std::invalid_argument when a property is not > 0.
void validate(const ElasticSectionProperties& p);

// d(EA, EI)/dtheta of properties p with seeds dp (product rule).
Vec2 rigidity_sensitivity(const ElasticSectionProperties& p, const ElasticSectionProperties& dp);

class ElasticSection final : public Section {
 public:
  explicit ElasticSection(const ElasticSectionProperties& p);

  void set_trial_deformation(const Vec2& e) override;
  const Vec2& deformation() const override { return e_; }
  const Vec2& resultant() const override { return s_; }
  const Mat2& tangent() const override { return k_; }
  Mat2 initial_tangent() const override { return k_; }
  double area() const override { return props_.A; }

  void commit() override { committed_e_ = e_; }
  void revert_to_last_commit() override { set_trial_deformation(committed_e_); }
  std::unique_ptr<Section> clone() const override;
  void archive(StateArchive& a) override;

  const ElasticSectionProperties& properties() const { return props_; }

  // --- DDM (no history: nothing to size or commit) ---
  void set_property_seed(int k, const ElasticSectionProperties& d) { seeds_.set(k, d); }
  void set_num_parameters(int) override {}
  Vec2 conditional_resultant_sensitivity(int k) const override;
  Mat2 initial_tangent_sensitivity(int k) const override;
  double area_sensitivity(int k) const override { return seeds_[k].A; }
  void set_deformation_sensitivity(int, const Vec2&) override {}

 private:
  ElasticSectionProperties props_;
  Mat2 k_;
  Vec2 e_ = Vec2::Zero();
  Vec2 s_ = Vec2::Zero();
  Vec2 committed_e_ = Vec2::Zero();
  Seeds<ElasticSectionProperties> seeds_;
};

}  // namespace pfem::structure
