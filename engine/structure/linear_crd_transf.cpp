#include "engine/structure/linear_crd_transf.h"

namespace pfem::structure {

LinearCrdTransf2d::LinearCrdTransf2d(const Vec2& xi, const Vec2& xj)
    : CrdTransf2d(xi, xj), B_(reference_basic_matrix()) {}

Mat6 LinearCrdTransf2d::global_stiffness(const Mat3& kb, const Vec3& /*q*/) const {
  return B_.transpose() * kb * B_;
}

std::unique_ptr<CrdTransf2d> LinearCrdTransf2d::clone() const {
  return std::make_unique<LinearCrdTransf2d>(*this);
}

void LinearCrdTransf2d::archive(StateArchive& a) { a(v_); }

}  // namespace pfem::structure
