#pragma once
// 2D corotational transformation (Crisfield 1991 vol. 1 ch. 7; OpenSees CorotCrdTransf2d).
//
// Current chord length Ln and direction (c, s); rigid chord rotation alpha = beta - beta0.
//   v = (Ln - L0, rzi - alpha, rzj - alpha)
//   r = dLn/du = (-c, -s, 0, c, s, 0),  z = (s, -c, 0, -s, c, 0),  dalpha/du = z/Ln
//   B = [r; e3 - z/Ln; e6 - z/Ln]
//   K = B^T kb B + N z z^T / Ln + (Mi + Mj) (r z^T + z r^T) / Ln^2
// The branch of alpha (atan2 gives (-pi, pi]) is the one closest to the mean end rotation,
// so a chain of elements may roll up by any angle (e.g. a cantilever into a full circle)
// as long as each element's own deformation stays below pi.
#include "engine/structure/crd_transf.h"

namespace pfem::structure {

class CorotationalCrdTransf2d final : public CrdTransf2d {
 public:
  CorotationalCrdTransf2d(const Vec2& xi, const Vec2& xj);

  TransfKind kind() const override { return TransfKind::kCorotational; }
  // Throws std::runtime_error if the chord collapses to zero length.
  void update(const Vec6& u) override;
  const Vec3& basic_deformation() const override { return v_; }
  const Mat36& basic_matrix() const override { return B_; }
  Vec6 global_force(const Vec3& q) const override;
  Mat6 global_stiffness(const Mat3& kb, const Vec3& q) const override;
  std::unique_ptr<CrdTransf2d> clone() const override;
  void archive(StateArchive& a) override;

  double current_length() const { return Ln_; }
  double chord_rotation() const { return alpha_; }

 private:
  Vec2 d0_;  // reference chord xj - xi
  double Ln_ = 0.0;
  double alpha_ = 0.0;
  Vec6 r_ = Vec6::Zero();
  Vec6 z_ = Vec6::Zero();
  Mat36 B_;
  Vec3 v_ = Vec3::Zero();
};

}  // namespace pfem::structure
