#pragma once
// Small-displacement transformation: v = B u with B fixed at the reference geometry.
#include "engine/structure/crd_transf.h"

namespace pfem::structure {

class LinearCrdTransf2d final : public CrdTransf2d {
 public:
  LinearCrdTransf2d(const Vec2& xi, const Vec2& xj);

  TransfKind kind() const override { return TransfKind::kLinear; }
  void update(const Vec6& u) override { v_ = B_ * u; }
  const Vec3& basic_deformation() const override { return v_; }
  const Mat36& basic_matrix() const override { return B_; }
  Vec6 global_force(const Vec3& q) const override { return B_.transpose() * q; }
  Mat6 global_stiffness(const Mat3& kb, const Vec3& q) const override;
  std::unique_ptr<CrdTransf2d> clone() const override;
  void archive(StateArchive& a) override;

 private:
  Mat36 B_;
  Vec3 v_ = Vec3::Zero();
};

}  // namespace pfem::structure
