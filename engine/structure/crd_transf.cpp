#include "engine/structure/crd_transf.h"

#include <algorithm>
#include <cmath>

#include "engine/structure/corotational_crd_transf.h"
#include "engine/structure/linear_crd_transf.h"
#include "engine/structure/validation.h"

namespace pfem::structure {

CrdTransf2d::CrdTransf2d(const Vec2& xi, const Vec2& xj) {
  const Vec2 d = xj - xi;
  L0_ = d.norm();
  const double scale = std::max(xi.norm(), xj.norm());
  if (!(L0_ > 1e-12 * scale) || L0_ == 0.0)
    throw_invalid("length", "zero-length beam (end nodes coincide)");
  c0_ = d(0) / L0_;
  s0_ = d(1) / L0_;
}

Mat36 CrdTransf2d::reference_basic_matrix() const {
  const double c = c0_, s = s0_, L = L0_;
  Mat36 B;
  // clang-format off
  B << -c, -s, 0.0, c, s, 0.0,
       -s / L, c / L, 1.0, s / L, -c / L, 0.0,
       -s / L, c / L, 0.0, s / L, -c / L, 1.0;
  // clang-format on
  return B;
}

Mat6 CrdTransf2d::reference_rotation() const {
  Mat6 T = Mat6::Zero();
  for (int n = 0; n < 2; ++n) {
    const int o = 3 * n;
    T(o, o) = c0_;
    T(o, o + 1) = s0_;
    T(o + 1, o) = -s0_;
    T(o + 1, o + 1) = c0_;
    T(o + 2, o + 2) = 1.0;
  }
  return T;
}

std::unique_ptr<CrdTransf2d> make_crd_transf(TransfKind kind, const Vec2& xi, const Vec2& xj) {
  if (kind == TransfKind::kCorotational) return std::make_unique<CorotationalCrdTransf2d>(xi, xj);
  return std::make_unique<LinearCrdTransf2d>(xi, xj);
}

}  // namespace pfem::structure
