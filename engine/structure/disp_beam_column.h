#pragma once
// Displacement-based 2D beam-column with a section at each Gauss-Legendre point.
// Basic-system interpolation on xi = x / L0 in [0, 1] (cubic transverse, linear axial):
//   eps0(xi) = v1 / L0,   kappa(xi) = ((6 xi - 4) v2 + (6 xi - 2) v3) / L0
//   q = sum_k L0 w_k b_k^T s_k,   kb = sum_k L0 w_k b_k^T ks_k b_k
// Two points (the default) integrate an elastic element exactly.
#include <vector>

#include "engine/structure/beam_column.h"
#include "engine/structure/gauss_legendre.h"
#include "engine/structure/section.h"

namespace pfem::structure {

class DispBeamColumn2d final : public BeamColumn2d {
 public:
  static constexpr int kMaxIntegrationPoints = 10;

  // Each integration point gets its own clone of `section`. Throws std::invalid_argument for
  // integration_points outside 1..10 ("integration_points"), negative rho ("rho") or a
  // zero-length beam ("length").
  DispBeamColumn2d(std::array<int, 2> nodes, const Vec2& xi, const Vec2& xj, const Section& section,
                   const BeamOptions& options = {}, int integration_points = 2);

  std::unique_ptr<Element> clone() const override;
  void set_num_parameters(int P) override;

  int num_integration_points() const { return static_cast<int>(sections_.size()); }
  const Section& section(int k) const { return *sections_[k]; }
  const QuadratureRule& quadrature() const { return rule_; }

 protected:
  DispBeamColumn2d(const DispBeamColumn2d& other);
  void compute_basic(const Vec3& v, Vec3& q, Mat3& kb) override;
  Mat3 initial_basic_stiffness() const override;
  void commit_basic() override;
  void revert_basic() override;
  void archive_basic(StateArchive& a) override;
  Vec3 conditional_basic_force_sensitivity(int k) const override;
  Mat3 initial_basic_stiffness_sensitivity(int k) const override;
  double section_area_sensitivity(int k) const override {
    return sections_[0]->area_sensitivity(k);
  }
  void set_basic_deformation_sensitivity(int k, const Vec3& dv) override;

 private:
  // Section deformations at point k: e = b_k v, b_k 2x3.
  Eigen::Matrix<double, 2, 3> strain_displacement(int k) const;

  QuadratureRule rule_;
  std::vector<std::unique_ptr<Section>> sections_;
};

}  // namespace pfem::structure
