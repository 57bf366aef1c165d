#include "engine/structure/corotational_crd_transf.h"

#include <cmath>
#include <numbers>
#include <stdexcept>

namespace pfem::structure {

CorotationalCrdTransf2d::CorotationalCrdTransf2d(const Vec2& xi, const Vec2& xj)
    : CrdTransf2d(xi, xj), d0_(xj - xi) {
  update(Vec6::Zero());
}

void CorotationalCrdTransf2d::update(const Vec6& u) {
  const double du = u(3) - u(0);
  const double dv = u(4) - u(1);
  const double dx = d0_(0) + du;
  const double dy = d0_(1) + dv;
  Ln_ = std::hypot(dx, dy);
  if (!(Ln_ > 0.0)) throw std::runtime_error("corotational beam: chord collapsed to zero length");
  const double c = dx / Ln_;
  const double s = dy / Ln_;

  // Rigid chord rotation, on the branch nearest the mean end rotation.
  const double sin_a = s * c0_ - c * s0_;
  const double cos_a = c * c0_ + s * s0_;
  const double two_pi = 2.0 * std::numbers::pi;
  alpha_ = std::atan2(sin_a, cos_a);
  const double mean_rotation = 0.5 * (u(2) + u(5));
  alpha_ += two_pi * std::round((mean_rotation - alpha_) / two_pi);

  r_ << -c, -s, 0.0, c, s, 0.0;
  z_ << s, -c, 0.0, -s, c, 0.0;
  B_.row(0) = r_.transpose();
  B_.row(1) = -z_.transpose() / Ln_;
  B_.row(2) = -z_.transpose() / Ln_;
  B_(1, 2) += 1.0;
  B_(2, 5) += 1.0;

  // Ln - L0 without cancellation: (Ln^2 - L0^2) / (Ln + L0).
  const double stretch = du * (2.0 * d0_(0) + du) + dv * (2.0 * d0_(1) + dv);
  v_ << stretch / (Ln_ + L0_), u(2) - alpha_, u(5) - alpha_;
}

Vec6 CorotationalCrdTransf2d::global_force(const Vec3& q) const { return B_.transpose() * q; }

Mat6 CorotationalCrdTransf2d::global_stiffness(const Mat3& kb, const Vec3& q) const {
  Mat6 K = B_.transpose() * kb * B_;
  K.noalias() += (q(0) / Ln_) * (z_ * z_.transpose());
  K.noalias() += ((q(1) + q(2)) / (Ln_ * Ln_)) * (r_ * z_.transpose() + z_ * r_.transpose());
  return K;
}

std::unique_ptr<CrdTransf2d> CorotationalCrdTransf2d::clone() const {
  return std::make_unique<CorotationalCrdTransf2d>(*this);
}

void CorotationalCrdTransf2d::archive(StateArchive& a) { a(Ln_), a(alpha_), a(r_), a(z_), a(B_), a(v_); }

}  // namespace pfem::structure
