#include "engine/structure/elastic_beam_column.h"

namespace pfem::structure {

namespace {
// The basic stiffness for the rigidities (EA, EI); linear in them, so also their derivative's.
Mat3 basic_stiffness_of(const Vec2& rigidity, double L) {
  const double ea = rigidity(0) / L;
  const double ei = rigidity(1) / L;
  Mat3 kb;
  // clang-format off
  kb << ea, 0.0, 0.0,
        0.0, 4.0 * ei, 2.0 * ei,
        0.0, 2.0 * ei, 4.0 * ei;
  // clang-format on
  return kb;
}
}  // namespace

ElasticBeamColumn2d::ElasticBeamColumn2d(std::array<int, 2> nodes, const Vec2& xi, const Vec2& xj,
                                         const ElasticSectionProperties& section,
                                         const BeamOptions& options,
                                         const Seeds<ElasticSectionProperties>& section_seeds)
    : BeamColumn2d(nodes, xi, xj, options), section_(section), seeds_(section_seeds) {
  validate(section);
  kb_elastic_ = basic_stiffness_of({section.E * section.A, section.E * section.I}, length());
  initialize(section.A);
}

void ElasticBeamColumn2d::compute_basic(const Vec3& v, Vec3& q, Mat3& kb) {
  kb = kb_elastic_;
  q = kb_elastic_ * v;
}

Mat3 ElasticBeamColumn2d::initial_basic_stiffness_sensitivity(int k) const {
  return basic_stiffness_of(rigidity_sensitivity(section_, seeds_[k]), length());
}

Vec3 ElasticBeamColumn2d::conditional_basic_force_sensitivity(int k) const {
  return initial_basic_stiffness_sensitivity(k) * basic_deformation();
}

std::unique_ptr<Element> ElasticBeamColumn2d::clone() const {
  return std::unique_ptr<Element>(new ElasticBeamColumn2d(*this));
}

}  // namespace pfem::structure
