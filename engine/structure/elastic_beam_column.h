#pragma once
// Elastic 2D beam-column (Euler-Bernoulli, exact basic stiffness):
//   q = (EA/L0 v1, EI/L0 (4 v2 + 2 v3), EI/L0 (2 v2 + 4 v3)).
// With the Corotational transformation it is the classic large-rotation, small-strain beam.
#include "engine/structure/beam_column.h"
#include "engine/structure/elastic_section.h"

namespace pfem::structure {

class ElasticBeamColumn2d final : public BeamColumn2d {
 public:
  // xi, xj: reference coordinates of nodes[0], nodes[1]. Throws std::invalid_argument for
  // non-positive E, A, I ("e", "a", "i"), negative rho ("rho") or a zero-length beam ("length").
  ElasticBeamColumn2d(std::array<int, 2> nodes, const Vec2& xi, const Vec2& xj,
                      const ElasticSectionProperties& section, const BeamOptions& options = {});

  std::unique_ptr<Element> clone() const override;
  const ElasticSectionProperties& section() const { return section_; }

 protected:
  void compute_basic(const Vec3& v, Vec3& q, Mat3& kb) override;
  Mat3 initial_basic_stiffness() const override { return kb_elastic_; }
  void commit_basic() override {}
  void revert_basic() override {}

 private:
  ElasticSectionProperties section_;
  Mat3 kb_elastic_;
};

}  // namespace pfem::structure
