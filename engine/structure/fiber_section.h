#pragma once
// Rectangular fiber section b x d split into n layers through the depth (midpoint rule).
// Fiber k sits at y_k = -d/2 + (k + 1/2) d/n with area b d/n and owns a clone of the material.
//
// Discretisation error of the midpoint rule (exact for linear integrands):
//   elastic  EI_n = E b d^3/12 (1 - 1/n^2),  EA_n = E b d (exact)
//   plastic  Mp_n = Fy b d^2/4 for n even, Fy b d^2/4 (1 - 1/n^2) for n odd.
//
// DDM: the section's seeds are d(b, d)/dtheta_k; the material seeds live in the fibers (seed
// the material before building the section). Fiber areas scale with b d and positions with
// d, so at fixed (eps0, kappa) a depth parameter also moves every fiber strain eps0 - y kappa.
#include <vector>

#include "engine/structure/section.h"
#include "engine/structure/seeds.h"
#include "engine/structure/uniaxial_material.h"

namespace pfem::structure {

struct FiberSectionGeometry {
  double width = 0.0;  // b, > 0
  double depth = 0.0;  // d, > 0
  int fibers = 0;      // n, >= 1
};

struct RectangleSeed {
  double width = 0.0;  // db/dtheta
  double depth = 0.0;  // dd/dtheta
};

class FiberSection final : public Section {
 public:
  // Throws std::invalid_argument: fields "width", "depth" (> 0), "fibers" (>= 1).
  FiberSection(const UniaxialMaterial& material, const FiberSectionGeometry& geometry);
  FiberSection(const FiberSection& other);
  FiberSection& operator=(const FiberSection&) = delete;

  void set_trial_deformation(const Vec2& e) override;
  const Vec2& deformation() const override { return e_; }
  const Vec2& resultant() const override { return s_; }
  const Mat2& tangent() const override { return k_; }
  Mat2 initial_tangent() const override;
  double area() const override { return geometry_.width * geometry_.depth; }

  void commit() override;
  void revert_to_last_commit() override;
  std::unique_ptr<Section> clone() const override;
  void archive(StateArchive& a) override;

  const FiberSectionGeometry& geometry() const { return geometry_; }
  int num_fibers() const { return static_cast<int>(fibers_.size()); }
  double fiber_y(int k) const { return y_[k]; }
  const UniaxialMaterial& fiber_material(int k) const { return *fibers_[k]; }

  // --- DDM ---
  void set_geometry_seed(int k, const RectangleSeed& d) { seeds_.set(k, d); }
  void set_num_parameters(int P) override;
  Vec2 conditional_resultant_sensitivity(int k) const override;
  Mat2 initial_tangent_sensitivity(int k) const override;
  double area_sensitivity(int k) const override;
  void set_deformation_sensitivity(int k, const Vec2& de) override;

 private:
  void update_resultants();
  // Per fiber: dA/dtheta_k (the same for all), and (dd/dtheta_k) / d, so that dy_i = y_i times it.
  double fiber_area_sensitivity(int k) const;
  double relative_depth_sensitivity(int k) const { return seeds_[k].depth / geometry_.depth; }

  FiberSectionGeometry geometry_;
  double fiber_area_ = 0.0;
  std::vector<double> y_;
  std::vector<std::unique_ptr<UniaxialMaterial>> fibers_;
  Vec2 e_ = Vec2::Zero();
  Vec2 committed_e_ = Vec2::Zero();
  Vec2 s_ = Vec2::Zero();
  Mat2 k_ = Mat2::Zero();
  Seeds<RectangleSeed> seeds_;
};

}  // namespace pfem::structure
