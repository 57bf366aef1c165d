#include "engine/structure/elastic_section.h"

#include "engine/structure/validation.h"

namespace pfem::structure {

void validate(const ElasticSectionProperties& p) {
  require_positive(p.E, "e");
  require_positive(p.A, "a");
  require_positive(p.I, "i");
}

ElasticSection::ElasticSection(const ElasticSectionProperties& p) : props_(p) {
  validate(p);
  k_ << p.E * p.A, 0.0, 0.0, p.E * p.I;
}

void ElasticSection::set_trial_deformation(const Vec2& e) {
  e_ = e;
  s_ = k_ * e;
}

Vec2 rigidity_sensitivity(const ElasticSectionProperties& p, const ElasticSectionProperties& dp) {
  return {dp.E * p.A + p.E * dp.A, dp.E * p.I + p.E * dp.I};
}

Vec2 ElasticSection::conditional_resultant_sensitivity(int k) const {
  return rigidity_sensitivity(props_, seeds_[k]).cwiseProduct(e_);
}

Mat2 ElasticSection::initial_tangent_sensitivity(int k) const {
  return rigidity_sensitivity(props_, seeds_[k]).asDiagonal();
}

std::unique_ptr<Section> ElasticSection::clone() const {
  return std::make_unique<ElasticSection>(*this);
}

void ElasticSection::archive(StateArchive& a) { a(e_), a(s_), a(committed_e_); }

}  // namespace pfem::structure
