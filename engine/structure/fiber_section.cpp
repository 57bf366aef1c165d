#include "engine/structure/fiber_section.h"

#include "engine/structure/validation.h"

namespace pfem::structure {

FiberSection::FiberSection(const UniaxialMaterial& material, const FiberSectionGeometry& geometry)
    : geometry_(geometry) {
  require_positive(geometry.width, "width");
  require_positive(geometry.depth, "depth");
  if (geometry.fibers < 1)
    throw_invalid("fibers", "must be >= 1 (got " + std::to_string(geometry.fibers) + ")");
  const int n = geometry.fibers;
  const double h = geometry.depth / n;
  fiber_area_ = geometry.width * h;
  y_.resize(n);
  fibers_.reserve(n);
  for (int k = 0; k < n; ++k) {
    y_[k] = -0.5 * geometry.depth + (k + 0.5) * h;
    fibers_.push_back(material.clone());
  }
  update_resultants();
}

FiberSection::FiberSection(const FiberSection& other)
    : geometry_(other.geometry_),
      fiber_area_(other.fiber_area_),
      y_(other.y_),
      e_(other.e_),
      committed_e_(other.committed_e_),
      s_(other.s_),
      k_(other.k_) {
  fibers_.reserve(other.fibers_.size());
  for (const auto& f : other.fibers_) fibers_.push_back(f->clone());
}

void FiberSection::set_trial_deformation(const Vec2& e) {
  e_ = e;
  for (std::size_t k = 0; k < fibers_.size(); ++k)
    fibers_[k]->set_trial_strain(e(0) - y_[k] * e(1));
  update_resultants();
}

void FiberSection::update_resultants() {
  s_.setZero();
  k_.setZero();
  for (std::size_t k = 0; k < fibers_.size(); ++k) {
    const double y = y_[k];
    const double force = fibers_[k]->stress() * fiber_area_;
    const double stiff = fibers_[k]->tangent() * fiber_area_;
    s_(0) += force;
    s_(1) -= force * y;
    k_(0, 0) += stiff;
    k_(0, 1) -= stiff * y;
    k_(1, 1) += stiff * y * y;
  }
  k_(1, 0) = k_(0, 1);
}

Mat2 FiberSection::initial_tangent() const {
  Mat2 k = Mat2::Zero();
  for (std::size_t i = 0; i < fibers_.size(); ++i) {
    const double stiff = fibers_[i]->initial_tangent() * fiber_area_;
    k(0, 0) += stiff;
    k(0, 1) -= stiff * y_[i];
    k(1, 1) += stiff * y_[i] * y_[i];
  }
  k(1, 0) = k(0, 1);
  return k;
}

void FiberSection::commit() {
  for (auto& f : fibers_) f->commit();
  committed_e_ = e_;
}

void FiberSection::revert_to_last_commit() {
  for (auto& f : fibers_) f->revert_to_last_commit();
  e_ = committed_e_;
  update_resultants();
}

std::unique_ptr<Section> FiberSection::clone() const {
  return std::make_unique<FiberSection>(*this);
}

}  // namespace pfem::structure
