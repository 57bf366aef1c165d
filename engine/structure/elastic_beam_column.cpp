#include "engine/structure/elastic_beam_column.h"

namespace pfem::structure {

ElasticBeamColumn2d::ElasticBeamColumn2d(std::array<int, 2> nodes, const Vec2& xi, const Vec2& xj,
                                         const ElasticSectionProperties& section,
                                         const BeamOptions& options)
    : BeamColumn2d(nodes, xi, xj, options), section_(section) {
  validate(section);
  const double L = length();
  const double ea = section.E * section.A / L;
  const double ei = section.E * section.I / L;
  // clang-format off
  kb_elastic_ << ea, 0.0, 0.0,
                 0.0, 4.0 * ei, 2.0 * ei,
                 0.0, 2.0 * ei, 4.0 * ei;
  // clang-format on
  initialize(section.A);
}

void ElasticBeamColumn2d::compute_basic(const Vec3& v, Vec3& q, Mat3& kb) {
  kb = kb_elastic_;
  q = kb_elastic_ * v;
}

std::unique_ptr<Element> ElasticBeamColumn2d::clone() const {
  return std::unique_ptr<Element>(new ElasticBeamColumn2d(*this));
}

}  // namespace pfem::structure
