#pragma once
// Elastic 2D beam-column (Euler-Bernoulli, exact basic stiffness):
//   q = (EA/L0 v1, EI/L0 (4 v2 + 2 v3), EI/L0 (2 v2 + 4 v3)).
// With the Corotational transformation it is the classic large-rotation, small-strain beam.
// DDM seeds: d(E, A, I)/dtheta_k (e.g. derived from a rectangle's width and depth).
#include "engine/structure/beam_column.h"
#include "engine/structure/elastic_section.h"

namespace pfem::structure {

class ElasticBeamColumn2d final : public BeamColumn2d {
 public:
  // xi, xj: reference coordinates of nodes[0], nodes[1]. Throws std::invalid_argument for
  // non-positive E, A, I ("e", "a", "i"), negative rho ("rho") or a zero-length beam ("length").
  ElasticBeamColumn2d(std::array<int, 2> nodes, const Vec2& xi, const Vec2& xj,
                      const ElasticSectionProperties& section, const BeamOptions& options = {},
                      const Seeds<ElasticSectionProperties>& section_seeds = {});

  std::unique_ptr<Element> clone() const override;
  const ElasticSectionProperties& section() const { return section_; }

 protected:
  void compute_basic(const Vec3& v, Vec3& q, Mat3& kb) override;
  Mat3 initial_basic_stiffness() const override { return kb_elastic_; }
  void commit_basic() override {}
  void revert_basic() override {}
  void archive_basic(StateArchive&) override {}  // no state of its own
  Vec3 conditional_basic_force_sensitivity(int k) const override;
  Mat3 initial_basic_stiffness_sensitivity(int k) const override;
  double section_area_sensitivity(int k) const override { return seeds_[k].A; }
  void set_basic_deformation_sensitivity(int, const Vec3&) override {}  // no history

 private:
  ElasticSectionProperties section_;
  Mat3 kb_elastic_;
  Seeds<ElasticSectionProperties> seeds_;
};

}  // namespace pfem::structure
