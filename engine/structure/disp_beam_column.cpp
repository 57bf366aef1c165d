#include "engine/structure/disp_beam_column.h"

#include "engine/structure/validation.h"

namespace pfem::structure {

namespace {
int checked_points(int n) {
  require_in_range(n, 1, DispBeamColumn2d::kMaxIntegrationPoints, "integration_points");
  return n;
}
}  // namespace

DispBeamColumn2d::DispBeamColumn2d(std::array<int, 2> nodes, const Vec2& xi, const Vec2& xj,
                                   const Section& section, const BeamOptions& options,
                                   int integration_points)
    : BeamColumn2d(nodes, xi, xj, options),
      rule_(gauss_legendre_01(checked_points(integration_points))) {
  sections_.reserve(integration_points);
  for (int k = 0; k < integration_points; ++k) sections_.push_back(section.clone());
  initialize(section.area());
}

DispBeamColumn2d::DispBeamColumn2d(const DispBeamColumn2d& other)
    : BeamColumn2d(other), rule_(other.rule_) {
  sections_.reserve(other.sections_.size());
  for (const auto& s : other.sections_) sections_.push_back(s->clone());
}

Eigen::Matrix<double, 2, 3> DispBeamColumn2d::strain_displacement(int k) const {
  const double L = length();
  const double xi = rule_.points[k];
  Eigen::Matrix<double, 2, 3> b;
  // clang-format off
  b << 1.0 / L, 0.0, 0.0,
       0.0, (6.0 * xi - 4.0) / L, (6.0 * xi - 2.0) / L;
  // clang-format on
  return b;
}

void DispBeamColumn2d::compute_basic(const Vec3& v, Vec3& q, Mat3& kb) {
  const double L = length();
  q.setZero();
  kb.setZero();
  for (std::size_t k = 0; k < sections_.size(); ++k) {
    const Eigen::Matrix<double, 2, 3> b = strain_displacement(static_cast<int>(k));
    Section& s = *sections_[k];
    s.set_trial_deformation(b * v);
    const double lw = L * rule_.weights[k];
    q.noalias() += lw * (b.transpose() * s.resultant());
    kb.noalias() += lw * (b.transpose() * s.tangent() * b);
  }
}

Mat3 DispBeamColumn2d::initial_basic_stiffness() const {
  const double L = length();
  Mat3 kb = Mat3::Zero();
  for (std::size_t k = 0; k < sections_.size(); ++k) {
    const Eigen::Matrix<double, 2, 3> b = strain_displacement(static_cast<int>(k));
    kb.noalias() += L * rule_.weights[k] * (b.transpose() * sections_[k]->initial_tangent() * b);
  }
  return kb;
}

void DispBeamColumn2d::commit_basic() {
  for (auto& s : sections_) s->commit();
}

void DispBeamColumn2d::revert_basic() {
  for (auto& s : sections_) s->revert_to_last_commit();
}

void DispBeamColumn2d::set_num_parameters(int P) {
  BeamColumn2d::set_num_parameters(P);
  for (auto& s : sections_) s->set_num_parameters(P);
}

Vec3 DispBeamColumn2d::conditional_basic_force_sensitivity(int k) const {
  Vec3 dq = Vec3::Zero();
  for (std::size_t i = 0; i < sections_.size(); ++i) {
    const Eigen::Matrix<double, 2, 3> b = strain_displacement(static_cast<int>(i));
    dq.noalias() += length() * rule_.weights[i] *
                    (b.transpose() * sections_[i]->conditional_resultant_sensitivity(k));
  }
  return dq;
}

Mat3 DispBeamColumn2d::initial_basic_stiffness_sensitivity(int k) const {
  Mat3 dkb = Mat3::Zero();
  for (std::size_t i = 0; i < sections_.size(); ++i) {
    const Eigen::Matrix<double, 2, 3> b = strain_displacement(static_cast<int>(i));
    dkb.noalias() += length() * rule_.weights[i] *
                     (b.transpose() * sections_[i]->initial_tangent_sensitivity(k) * b);
  }
  return dkb;
}

void DispBeamColumn2d::set_basic_deformation_sensitivity(int k, const Vec3& dv) {
  for (std::size_t i = 0; i < sections_.size(); ++i)
    sections_[i]->set_deformation_sensitivity(k, strain_displacement(static_cast<int>(i)) * dv);
}

std::unique_ptr<Element> DispBeamColumn2d::clone() const {
  return std::unique_ptr<Element>(new DispBeamColumn2d(*this));
}

void DispBeamColumn2d::archive_basic(StateArchive& a) {
  a.expect(sections_.size(), "integration points of a beam");
  for (auto& s : sections_) s->archive(a);
}

}  // namespace pfem::structure
