#include "engine/structure/beam_column.h"

#include "engine/structure/validation.h"

namespace pfem::structure {

Mat6 beam_mass_matrix(double m, const CrdTransf2d& transf, MassKind kind) {
  const double L = transf.initial_length();
  Mat6 M = Mat6::Zero();
  if (kind == MassKind::kLumped) {
    const double half = 0.5 * m * L;
    M(0, 0) = M(1, 1) = M(3, 3) = M(4, 4) = half;
    return M;  // rotation-invariant: no transformation needed
  }
  // Local (axial u, transverse w, rotation) at both ends.
  const double a = m * L / 6.0;
  M(0, 0) = M(3, 3) = 2.0 * a;
  M(0, 3) = M(3, 0) = a;
  const double t = m * L / 420.0;
  const int w[4] = {1, 2, 4, 5};
  const double h[4][4] = {{156.0, 22.0 * L, 54.0, -13.0 * L},
                          {22.0 * L, 4.0 * L * L, 13.0 * L, -3.0 * L * L},
                          {54.0, 13.0 * L, 156.0, -22.0 * L},
                          {-13.0 * L, -3.0 * L * L, -22.0 * L, 4.0 * L * L}};
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c) M(w[r], w[c]) = t * h[r][c];
  const Mat6 T = transf.reference_rotation();
  return T.transpose() * M * T;
}

BeamColumn2d::BeamColumn2d(std::array<int, 2> nodes, const Vec2& xi, const Vec2& xj,
                           const BeamOptions& o)
    : nodes_(nodes), options_(o), transf_(make_crd_transf(o.transf, xi, xj)) {
  require_non_negative(o.rho, "rho");
}

BeamColumn2d::BeamColumn2d(const BeamColumn2d& other)
    : Element(other),
      nodes_(other.nodes_),
      options_(other.options_),
      transf_(other.transf_->clone()),
      section_area_(other.section_area_),
      mass_per_length_(other.mass_per_length_),
      committed_u_(other.committed_u_),
      q_(other.q_),
      kb_(other.kb_),
      force_(other.force_),
      tangent_(other.tangent_),
      initial_stiffness_(other.initial_stiffness_),
      mass_(other.mass_),
      trial_u_(other.trial_u_),
      basic_force_sens_(other.basic_force_sens_) {}

void BeamColumn2d::initialize(double section_area) {
  section_area_ = section_area;
  mass_per_length_ = options_.rho * section_area;
  mass_ = beam_mass_matrix(mass_per_length_, *transf_, options_.mass);
  const Mat36 B0 = transf_->reference_basic_matrix();
  initial_stiffness_ = B0.transpose() * initial_basic_stiffness() * B0;
  set_trial_displacement(Vec6::Zero());
}

void BeamColumn2d::set_trial_displacement(const Vec6& u) {
  trial_u_ = u;
  transf_->update(u);
  compute_basic(transf_->basic_deformation(), q_, kb_);
  force_ = transf_->global_force(q_);
  tangent_ = transf_->global_stiffness(kb_, q_);
}

void BeamColumn2d::commit() {
  commit_basic();
  committed_u_ = trial_u_;
}

void BeamColumn2d::revert_to_last_commit() {
  revert_basic();
  set_trial_displacement(committed_u_);
}

void BeamColumn2d::set_num_parameters(int P) { basic_force_sens_.assign(P, Vec3::Zero()); }

Vec6 BeamColumn2d::conditional_force_sensitivity(int k) const {
  return transf_->global_force(conditional_basic_force_sensitivity(k));
}

Mat6 BeamColumn2d::mass_sensitivity(int k) const {
  const double dm =
      options_.rho_seeds[k] * section_area_ + options_.rho * section_area_sensitivity(k);
  return beam_mass_matrix(dm, *transf_, options_.mass);  // M is linear in m
}

Mat6 BeamColumn2d::initial_stiffness_sensitivity(int k) const {
  const Mat36 B0 = transf_->reference_basic_matrix();
  return B0.transpose() * initial_basic_stiffness_sensitivity(k) * B0;
}

void BeamColumn2d::set_displacement_sensitivity(int k, const Vec6& du) {
  const Vec3 dv = transf_->basic_matrix() * du;
  basic_force_sens_.at(k) = kb_ * dv + conditional_basic_force_sensitivity(k);
  set_basic_deformation_sensitivity(k, dv);
}

void BeamColumn2d::archive(StateArchive& a) {
  a(committed_u_), a(trial_u_), a(q_), a(kb_), a(force_), a(tangent_);
  a.expect(basic_force_sens_.size(), "parameters of a beam");
  for (auto& s : basic_force_sens_) a(s);
  transf_->archive(a);
  archive_basic(a);
}

}  // namespace pfem::structure
