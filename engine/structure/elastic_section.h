#pragma once
// Linear elastic section: N = EA eps0, M = EI kappa.
#include "engine/structure/section.h"

namespace pfem::structure {

struct ElasticSectionProperties {
  double E = 0.0;  // Young's modulus, > 0   (field "e")
  double A = 0.0;  // area, > 0              (field "a")
  double I = 0.0;  // second moment, > 0     (field "i")
};

// Throws std::invalid_argument when a property is not > 0.
void validate(const ElasticSectionProperties& p);

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

  const ElasticSectionProperties& properties() const { return props_; }

 private:
  ElasticSectionProperties props_;
  Mat2 k_;
  Vec2 e_ = Vec2::Zero();
  Vec2 s_ = Vec2::Zero();
  Vec2 committed_e_ = Vec2::Zero();
};

}  // namespace pfem::structure
