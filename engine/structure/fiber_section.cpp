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
      k_(other.k_),
      seeds_(other.seeds_) {
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

void FiberSection::set_num_parameters(int P) {
  for (auto& f : fibers_) f->set_num_parameters(P);
}

double FiberSection::area_sensitivity(int k) const {
  return seeds_[k].width * geometry_.depth + geometry_.width * seeds_[k].depth;
}

double FiberSection::fiber_area_sensitivity(int k) const {
  return area_sensitivity(k) / num_fibers();
}

Vec2 FiberSection::conditional_resultant_sensitivity(int k) const {
  const double dA = fiber_area_sensitivity(k);
  const double rd = relative_depth_sensitivity(k);
  Vec2 ds = Vec2::Zero();
  for (std::size_t i = 0; i < fibers_.size(); ++i) {
    const UniaxialMaterial& m = *fibers_[i];
    const double y = y_[i], dy = y * rd;
    const double dstress = m.tangent() * (-dy * e_(1)) + m.conditional_stress_sensitivity(k);
    const double dforce = dstress * fiber_area_ + m.stress() * dA;
    ds(0) += dforce;
    ds(1) -= dforce * y + m.stress() * fiber_area_ * dy;
  }
  return ds;
}

Mat2 FiberSection::initial_tangent_sensitivity(int k) const {
  const double dA = fiber_area_sensitivity(k);
  const double rd = relative_depth_sensitivity(k);
  Mat2 dk = Mat2::Zero();
  for (std::size_t i = 0; i < fibers_.size(); ++i) {
    const double y = y_[i], dy = y * rd;
    const double stiff = fibers_[i]->initial_tangent() * fiber_area_;
    const double dstiff = fibers_[i]->initial_tangent_sensitivity(k) * fiber_area_ +
                          fibers_[i]->initial_tangent() * dA;
    dk(0, 0) += dstiff;
    dk(0, 1) -= dstiff * y + stiff * dy;
    dk(1, 1) += dstiff * y * y + 2.0 * stiff * y * dy;
  }
  dk(1, 0) = dk(0, 1);
  return dk;
}

void FiberSection::set_deformation_sensitivity(int k, const Vec2& de) {
  const double rd = relative_depth_sensitivity(k);
  for (std::size_t i = 0; i < fibers_.size(); ++i)
    fibers_[i]->set_strain_sensitivity(k, de(0) - y_[i] * (rd * e_(1) + de(1)));
}

std::unique_ptr<Section> FiberSection::clone() const {
  return std::make_unique<FiberSection>(*this);
}

void FiberSection::archive(StateArchive& a) {
  a(e_), a(committed_e_), a(s_), a(k_);
  a.expect(fibers_.size(), "fibers of a section");
  for (auto& f : fibers_) f->archive(a);
}

}  // namespace pfem::structure
